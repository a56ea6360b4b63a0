/// \file triangle.cpp
/// \brief Ray/triangle kernels (Möller–Trumbore, watertight), block boxes and the leaf triangle
/// store, written once over lanes::VFloat<L> and instantiated for 16, 8 and 1 lanes.
///
/// Compiled with -ffp-contract=off (src/accel/CMakeLists.txt): see triangle.h for why every
/// width must give bit-identical results.
// GCC 12's _mm512_max_ps / _mm512_min_ps expand to _mm512_undefined_ps(), which -Wuninitialized
// reports once inlined here; the value is never read.
#pragma GCC diagnostic ignored "-Wuninitialized"

#include "triangle.h"
#include "exact_edges.h"
#include "lanes.h"
#include "select_smallest.h"
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

#ifdef NORI_OCTREE_COUNTERS
#include "octree.h"
#define NORI_TRIANGLE_COUNT(field, n) (g_octreeCounters.field += (n))
#else
#define NORI_TRIANGLE_COUNT(field, n) ((void)0)
#endif

namespace nori {

using lanes::kMaxLanes;
using lanes::VFloat;
using lanes::VMask;

Intersector parseIntersector(const PropertyList &props, const std::string &defaultValue) {
    std::string name = props.getString("intersector", defaultValue);
    if (name == "mt") return Intersector::MT;
    if (name == "watertight") return Intersector::Watertight;
    props.fail("intersector", fmt::format("unknown intersector '{}' (allowed: mt, watertight)", name));
}

const char *intersectorName(Intersector kind) { return kind == Intersector::MT ? "mt" : "watertight"; }

bool triangleCanBeHit(const std::array<Point3f, 3> &v) {
    if (!(v[0].allFinite() && v[1].allFinite() && v[2].allFinite())) return false;
    // Most triangles are settled by their float normal: a difference of floats is within a
    // relative 2^-24 of the exact one, so each component of the cross product is within 4 units
    // of 2^-24 of its two products' magnitudes; one beyond 2^-20 of them (and clear of the
    // subnormal range, where products lose their relative precision) is nonzero.
    const Vector3f a = v[1] - v[0], b = v[2] - v[0];
    bool nonzero = false;
    for (int e = 0; e < 3; ++e) {
        const int i = (e + 1) % 3, j = (e + 2) % 3;
        const float x = a[i] * b[j], y = a[j] * b[i];
        nonzero |= std::abs(x - y) > 0x1p-20f * (std::abs(x) + std::abs(y)) + 0x1p-100f;
    }
    if (nonzero) return true;
    const float p[3][3] = {{v[0].x(), v[0].y(), v[0].z()}, {v[1].x(), v[1].y(), v[1].z()}, {v[2].x(), v[2].y(), v[2].z()}};
    return !exactlyCollinear(p);
}

TriangleRay::TriangleRay(const Ray3f &ray, float cullAbsOfRay) : cullAbs(cullAbsOfRay) {
    // Component by component: a loop over the Eigen vectors compiled to two calls of memmove.
    o[0] = ray.o.x(), o[1] = ray.o.y(), o[2] = ray.o.z();
    d[0] = ray.d.x(), d[1] = ray.d.y(), d[2] = ray.d.z();
    mint = ray.mint;
    // Everything below reads the ray, not the copies just stored: the compiler stores them in
    // pairs, and a read of two floats spanning two such stores cannot be forwarded from them
    // (it waits for both to reach the cache, a third of this constructor's time).
    // Woop et al. 2013, section 3: shear/scale so that the ray becomes the +z axis.
    const float ax = std::abs(ray.d.x()), ay = std::abs(ray.d.y()), az = std::abs(ray.d.z());
    kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    kx = kz == 2 ? 0 : kz + 1;
    ky = kx == 2 ? 0 : kx + 1;
    if (ray.d[kz] < 0.0f) std::swap(kx, ky);
    sx = ray.d[kx] / ray.d[kz];
    sy = ray.d[ky] / ray.d[kz];
    sz = ray.dRcp[kz];  // 1 / d[kz], the same bits (Ray3f::update), one division fewer
    for (int a = 0; a < 3; ++a) {
        neg[a] = std::signbit(ray.d[a]) ? 1 : 0;
        rcpNear[a] = ray.dRcp[a] * (1.0f - 0x1p-20f);
        rcpFar[a] = ray.dRcp[a] * (1.0f + 0x1p-20f);
    }
}

// ---------------------------------------------------------------------------------------------

void TriangleStore::reset(Intersector kind, size_t words) {
    m_kind = kind;
    m_data.clear();
    m_data.shrink_to_fit();
    m_data.resize(words);  // uninitialised (see m_data), exactly `words` of capacity
}

namespace {
/// A leaf's triangle in the chunk order: three times its centroid (the key: only its order
/// matters) and its index in the leaf (`setLeaf`'s \p ids and \p bounds).
struct alignas(16) Keyed {
    Point3f centroid;
    uint32_t local;
};

/// A Keyed as one vector (x, y, z, local's bits), so that the selection moves it with one
/// load and one store (as a struct, with four). Its natural 16-byte alignment, which Keyed
/// shares: a template (selectSmallest) deduces the vector type without a typedef's alignment
/// attribute, so an under-aligned KeyedVec would reach it as a 16-byte aligned one.
typedef float KeyedVec __attribute__((vector_size(16), may_alias));
static_assert(sizeof(Keyed) == sizeof(KeyedVec) && alignof(Keyed) == alignof(KeyedVec), "Keyed: (x, y, z, local) in one vector");

inline uint32_t localOf(const KeyedVec &k) {
    uint32_t i;
    std::memcpy(&i, reinterpret_cast<const char *>(&k) + 12, sizeof i);
    return i;
}

/// A box as two (x, y, z, 0) vectors, empty until something is added: a triangle's bounds
/// clipped to its leaf's box, or the union of several.
struct Box4 {
    KeyedVec lo = KeyedVec{} + Infinity, hi = KeyedVec{} - Infinity;
    void add(const Box4 &b) {
        lo = b.lo < lo ? b.lo : lo;
        hi = b.hi > hi ? b.hi : hi;
    }
    float halfArea() const {
        const KeyedVec e = hi - lo;
        return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
    }
};

/// The bounds of items [begin, end).
inline Box4 boundsOf(const KeyedVec *items, uint32_t begin, uint32_t end, const Box4 *bounds) {
    Box4 u;
    for (uint32_t i = begin; i < end; ++i) u.add(bounds[localOf(items[i])]);
    return u;
}

/// Rearrange [first, last) so that the kth - first items smallest along \p axis come first.
inline void selectAlong(int axis, KeyedVec *first, KeyedVec *kth, KeyedVec *last) {
    // (The chunks' sets as std::nth_element makes them, up to ties, in less time on large
    // leaves: see selectSmallest(). pa5 table's build 4.9 -> 4.2 ms.)
    switch (axis) {
    case 0: selectSmallest(first, kth, last, [](const KeyedVec &k) { return k[0]; }); break;
    case 1: selectSmallest(first, kth, last, [](const KeyedVec &k) { return k[1]; }); break;
    default: selectSmallest(first, kth, last, [](const KeyedVec &k) { return k[2]; }); break;
    }
}

/// How far the halves' areas must exceed the bound of disjoint halves (see orderChunks()) for
/// the other axes to be tried: 1.0 and 1.1 order the chunks alike (primary rays test 19.22 and
/// 19.24 chunks in grass, 1.62 and 1.63 in the city, 3.37 and 3.39 in the forest), and 1.1
/// costs pa5 table's build 5.5 % more instructions instead of 9.3 % (callgrind).
constexpr float kOverlapMargin = 1.1f;

/// Order [begin, end) so that every aligned run of 16, and each of its blocks of \p block
/// (8 or 16: TriangleStore::blockSize), is spatially compact: split at a multiple of 16 (of 8
/// within a run of 16), recursively, as a BVH's bottom levels are built by median splits.
///
/// The split is along the longest axis of the centroids, unless the two halves' boxes
/// overlap: their half-areas add up to more than those of their union cut in two across that
/// axis (for a union of extents (a, b, c) cut across a: its half-area plus b c), by
/// kOverlapMargin. Then the other axes are tried too and the one whose halves have the least
/// area wins (the surface area heuristic, MacDonald & Booth 1990). Small triangles on a
/// surface rarely overlap so; long slanted ones do (grass blades, cut across their height,
/// leave both halves as tall as the whole; a city's walls). Per primary ray, grass tests 21.5
/// -> 19.2 chunks, the city 1.76 -> 1.63, the forest 3.54 -> 3.40, pa5 table 1.80 -> 1.70,
/// the 203k dragon 0.47 -> 0.46 (diffuse 2.58 -> 2.56). Only the 16s are chosen so, the
/// chunks a sixteen-lane step tests: the 8s within them gain little (grass nothing) and
/// would cost build time. \p spare (as long as \p items) holds the best split while others
/// are tried.
void orderChunks(KeyedVec *items, uint32_t begin, uint32_t end, uint32_t block, const Box4 *bounds,
                 KeyedVec *spare) {
    if (end - begin <= block) return;
    // The centroids' box as BoundingBox3f::expandBy makes it, four lanes at a time (the
    // fourth, local's bits, unused).
    KeyedVec lo = KeyedVec{} + Infinity, hi = KeyedVec{} - Infinity;
    for (uint32_t i = begin; i < end; ++i) {
        const KeyedVec c = items[i];
        lo = c < lo ? c : lo;
        hi = c > hi ? c : hi;
    }
    const int longest = BoundingBox3f(Point3f(lo[0], lo[1], lo[2]), Point3f(hi[0], hi[1], hi[2])).majorAxis();
    const uint32_t unit = end - begin > 16 ? 16 : 8;
    const uint32_t units = (end - begin + unit - 1) / unit, mid = begin + unit * ((units + 1) / 2);
    KeyedVec *first = items + begin, *kth = items + mid, *last = items + end;
    selectAlong(longest, first, kth, last);
    if (unit == 16) {
        const Box4 below = boundsOf(items, begin, mid, bounds), above = boundsOf(items, mid, end, bounds);
        Box4 all = below;
        all.add(above);
        const KeyedVec e = all.hi - all.lo;
        const float areas = below.halfArea() + above.halfArea();
        if (areas > kOverlapMargin * (all.halfArea() + e[(longest + 1) % 3] * e[(longest + 2) % 3])) {
            // The best split so far is kept in \p spare (a copy costs less than selecting again).
            int others[2], count = 0;
            for (int a = 0; a < 3; ++a)
                if (a != longest && hi[a] > lo[a]) others[count++] = a;  // (all on one plane: no split)
            const size_t bytes = sizeof(KeyedVec) * (end - begin);
            std::memcpy(spare + begin, items + begin, bytes);
            bool bestKept = true;  // the items hold the best split (else spare does)
            float bestAreas = areas;
            for (int k = 0; k < count; ++k) {
                selectAlong(others[k], first, kth, last);
                const float other = boundsOf(items, begin, mid, bounds).halfArea() + boundsOf(items, mid, end, bounds).halfArea();
                bestKept = other < bestAreas;
                if (bestKept) {
                    bestAreas = other;
                    if (k + 1 < count) std::memcpy(spare + begin, items + begin, bytes);
                }
            }
            if (!bestKept) std::memcpy(items + begin, spare + begin, bytes);
        }
    }
    orderChunks(items, begin, mid, block, bounds, spare);
    orderChunks(items, mid, end, block, bounds, spare);
}
} // namespace

void TriangleStore::setLeaf(size_t offset, const uint32_t *ids, uint32_t n, const std::array<Point3f, 3> *vertices,
                            const BoundingBox3f *clip) {
    // Corners prefetched this many triangles ahead (scattered ids; the leaf's loops wait on
    // these loads more than on anything else): a leaf of up to 16 requests all at once.
    constexpr uint32_t kAhead = 16;
    if (n == 0) return;  // an empty leaf has no block (and an empty store no data to copy into)
    float *rows = m_data.data() + offset;
    // The corner rows of the triangles prims[0 .. n - 1], in that order.
    auto copyCorners = [&](const uint32_t *prims) {
        for (uint32_t i = 0; i < std::min(n, kAhead); ++i) __builtin_prefetch(&vertices[prims[i]]);
        for (uint32_t i = 0; i < n; ++i) {
            if (i + kAhead < n) __builtin_prefetch(&vertices[prims[i + kAhead]]);
            const std::array<Point3f, 3> &p = vertices[prims[i]];
            for (int v = 0; v < 3; ++v)
                for (int c = 0; c < 3; ++c) rows[(3 * v + c) * n + i] = p[v][c];
        }
    };
    if (n <= 16) {
        // One chunk, in the given order, without blocks.
        std::memcpy(rows + size_t(9) * n, ids, sizeof(uint32_t) * n);
        copyCorners(ids);
        return;
    }
    // Scratch space reused by every leaf a thread writes (no allocation per leaf): the keys,
    // then the bounds (two keys' room each). It only grows: resizing it down and up again
    // zero-filled the regrown part for most leaves (0.8 % of the octree build's instructions
    // on pa5 table, 0.4 % on the city), and every word used is written below before it is read.
    thread_local std::vector<Keyed> scratch;
    if (scratch.size() < 4 * size_t(n)) scratch.resize(4 * size_t(n));
    Keyed *items = scratch.data();
    Box4 *bounds = reinterpret_cast<Box4 *>(scratch.data() + n);
    KeyedVec *spare = reinterpret_cast<KeyedVec *>(scratch.data() + 3 * size_t(n));
    for (uint32_t i = 0; i < kAhead; ++i) __builtin_prefetch(&vertices[ids[i]]);
    for (uint32_t i = 0; i < n; ++i) {
        if (i + kAhead < n) __builtin_prefetch(&vertices[ids[i + kAhead]]);
        const std::array<Point3f, 3> &v = vertices[ids[i]];
        Point3f key = v[0] + v[1] + v[2];
        Point3f lo = v[0].cwiseMin(v[1]).cwiseMin(v[2]), hi = v[0].cwiseMax(v[1]).cwiseMax(v[2]);
        if (clip && (!clip->contains(lo) || !clip->contains(hi))) {
            // A triangle reaching out of the leaf is ordered and boxed by the part inside it
            // (a ray meets its other parts in the other cells that hold it: a long wall's
            // block would otherwise reach far out of the leaf, and every ray crossing the leaf
            // would test it). The key: three times the clipped bounds' centre, the scale of
            // the others.
            lo = lo.cwiseMax(clip->min);
            hi = hi.cwiseMin(clip->max);
            key = 1.5f * (lo + hi);
        }
        items[i] = {key, i};
        bounds[i].lo = KeyedVec{lo.x(), lo.y(), lo.z(), 0.0f};
        bounds[i].hi = KeyedVec{hi.x(), hi.y(), hi.z(), 0.0f};
    }
    orderChunks(reinterpret_cast<KeyedVec *>(items), 0, n, blockSize(n), bounds, spare);
    // Ids and corners in that order.
    uint32_t *prims = reinterpret_cast<uint32_t *>(rows + size_t(9) * n);
    for (uint32_t i = 0; i < n; ++i) prims[i] = ids[items[i].local];
    copyCorners(prims);
    // Block boxes, structure of arrays: rows min x, y, z, max x, y, z of nb floats.
    const uint32_t nb = blockCount(n), size = blockSize(n);
    float *boxes = rows + size_t(10) * n;
    for (uint32_t k = 0; k < nb; ++k) {
        Box4 b;
        for (uint32_t i = size * k; i < std::min(n, size * k + size); ++i) b.add(bounds[items[i].local]);
        for (int a = 0; a < 3; ++a) {
            boxes[size_t(a) * nb + k] = b.lo[a];
            boxes[size_t(3 + a) * nb + k] = b.hi[a];
        }
    }
}

namespace {

inline uint32_t primAt(const float *rows, uint32_t n, uint32_t i) {
    uint32_t p;
    std::memcpy(&p, rows + size_t(9) * n + i, sizeof(uint32_t));
    return p;
}

/// Row \p row of a leaf (stride n) at triangles i .. i + L - 1; lanes outside \p m are zero.
/// (The step kernels are forced inline: as calls, their results would travel through memory.)
template <int L>
inline VFloat<L> loadRow(const float *rows, uint32_t n, int row, uint32_t i, VMask<L> m) {
    return VFloat<L>::load(rows + size_t(row) * n + i, m);
}

/// One kernel step over L consecutive triangles of a leaf: per lane t, u, v and whether the
/// lane is a hit with t in [mint, maxt] (t, u, v are meaningless in the other lanes).
template <int L>
struct Step {
    VFloat<L> t, u, v;
    VMask<L> hit;
    VMask<L> known{};  ///< for the tests: t from exactPlaneT, crossing known inside (test skipped)
};

/// Scale of the problem for the t error estimates, in units of t: |d|_inf = |d[kz]|, 1 / |d|_inf
/// and |o|_inf / |d|_inf (the origin's magnitude). Computed only in steps with a hit.
struct TScale {
    float dInf, rcpDInf, oScale;
    explicit TScale(const TriangleRay &r)
        : dInf(std::abs(r.d[r.kz])), rcpDInf(std::abs(r.sz)),
          oScale(std::max({std::abs(r.o[0]), std::abs(r.o[1]), std::abs(r.o[2])}) * std::abs(r.sz)) {}
};

/// The lanes of \p valid whose float t, with first-order error estimate \p err, needs the double
/// t: err exceeds 2^-19 of the problem's scale (|t| + |o|_inf / |d|_inf), unless the lane lies
/// behind mint by more than err, or beyond maxt by more than 4 err (then the float range test
/// rejects it, as it would the exact t: the lanes behind the origin or far beyond the closest hit
/// so far, most lanes of a huge triangle). The wider margin beyond maxt keeps the choice
/// between float and double t independent of the order in which an accelerator visits leaves
/// (maxt is the closest hit so far) wherever the estimate holds within a factor 4. A NaN
/// estimate takes the double path.
template <int L>
inline VMask<L> needsExactT(VMask<L> valid, VFloat<L> t, VFloat<L> err, float oScale, float mint, float maxt) {
    const VMask<L> outside = (t + err < mint) | (t - VFloat<L>(4.0f) * err > maxt);
    return valid & ~(err <= VFloat<L>(0x1p-19f) * (abs(t) + oScale)) & ~outside;
}

/// For an any-hit query: the lanes of \p inside (crossing surely inside the triangle) whose
/// float t lies within [mint, maxt] by more than 4 \p err, the margin needsExactT grants beyond
/// maxt. Their exact t lies in the range too wherever the estimate holds within that factor, so
/// the double t (exactPlaneT) would change no decision: a ray leaving a floor toward a light
/// behind a ceiling is occluded whatever the ceiling's t rounds to.
template <int L>
inline VMask<L> surelyInRange(VMask<L> inside, VFloat<L> t, VFloat<L> err, float mint, float maxt) {
    const VFloat<L> margin = VFloat<L>(4.0f) * err;
    return inside & (t - margin >= mint) & (t + margin <= maxt);
}

/// x rounded to float, except that a nonzero x too small for a float keeps its sign (as the
/// smallest subnormal): only the sign of an edge function (or of t) decides a hit.
inline float signedFloat(double x) {
    const float f = float(x);
    return f != 0.0f || x == 0.0 ? f : std::copysign(std::numeric_limits<float>::denorm_min(), f);
}

/// The lanes of \p redo get t again from the plane equation in double precision,
/// t = n.(p0 - o) / (n.d) with n = (p1 - p0) x (p2 - p0), on the stored (exact) corners; the
/// other lanes keep \p t. The differences of floats are exact in double (up to a relative 2^-53
/// when their exponents are more than 29 apart), so the result is t of the exact triangle and
/// ray up to a few double roundings amplified by the triangle's shape and the ray's grazing
/// angle: far below float precision. Rare and out of line: taken where the float t's error
/// estimate exceeds its tolerance. A lane holding \p skipPrim (the closest hit so far, met again
/// in another leaf) is no hit: its t is known already. The lanes of \p inside are known to cross
/// the plane strictly inside the triangle (the kernel's barycentrics exceed their rounding
/// error bound, or the watertight kernel's exact edge volumes are all nonzero): they skip the
/// inside test below, which they would pass.
template <int L>
[[gnu::noinline]] VFloat<L> exactPlaneT(VMask<L> redo, VMask<L> inside, const TriangleRay &r, const float *rows,
                                        uint32_t n, uint32_t i, VFloat<L> t, uint32_t skipPrim) {
    // Not [[gnu::cold]]: GCC optimizes cold functions for size, which turned the nine corner
    // loads into loops through the stack (twice the instructions of this straight-line code).
    VFloat<L> out = t;
    NORI_TRIANGLE_COUNT(exactT, __builtin_popcount(bits(redo)));
    const size_t s = n;  // row stride
    for (unsigned b = bits(redo); b; b &= b - 1) {
        const int j = __builtin_ctz(b);
        const float *c = rows + i + uint32_t(j);  // corner coordinates of lane j: c[row * s]
        if (primAt(rows, n, i + uint32_t(j)) == skipPrim) {  // already the closest hit: no news
            out = withLane(out, j, std::numeric_limits<float>::quiet_NaN());
            continue;
        }
        if (bits(inside) >> j & 1u) {
            // An axis-aligned triangle (a floor, a wall: the huge triangles that come here most)
            // lies in the plane x_a = p0_a: t = (p0_a - o_a) / d_a, a difference of floats
            // (exact in double up to a relative 2^-53) and one division, instead of the normal
            // and two dot products below. The exact t is the same; its rounding may differ by
            // an ulp of double.
            const int a = c[0] == c[3 * s] && c[0] == c[6 * s]           ? 0
                          : c[s] == c[4 * s] && c[s] == c[7 * s]         ? 1
                          : c[2 * s] == c[5 * s] && c[2 * s] == c[8 * s] ? 2
                                                                         : -1;
            if (a >= 0 && r.d[a] != 0.0f) {
                out = withLane(out, j, signedFloat((double(c[size_t(a) * s]) - double(r.o[a])) / double(r.d[a])));
                continue;
            }
        }
        const double p0x = c[0], p0y = c[s], p0z = c[2 * s];
        const double e1[3] = {c[3 * s] - p0x, c[4 * s] - p0y, c[5 * s] - p0z};
        const double e2[3] = {c[6 * s] - p0x, c[7 * s] - p0y, c[8 * s] - p0z};
        const double w[3] = {p0x - double(r.o[0]), p0y - double(r.o[1]), p0z - double(r.o[2])};
        const double nx = e1[1] * e2[2] - e1[2] * e2[1], ny = e1[2] * e2[0] - e1[0] * e2[2],
                     nz = e1[0] * e2[1] - e1[1] * e2[0];
        const double num = nx * w[0] + ny * w[1] + nz * w[2];
        const double den = nx * double(r.d[0]) + ny * double(r.d[1]) + nz * double(r.d[2]);
        if (den == 0.0) continue;  // the ray lies in the plane: the float t stays (see below)
        const double te = num / den;
        if (bits(inside) >> j & 1u) {
            out = withLane(out, j, signedFloat(te));
            continue;
        }
        // The kernel's edge test let the lane through: mt's float test (kept), or the watertight
        // kernel's exact one for a crossing on an edge (its other lanes skip this). Where the
        // exact crossing lies off the triangle (a barycentric coordinate below -2^-24, about
        // the rounding of this double computation on a sliver), i.e. for a ray within the
        // edge test's rounding of an edge at a grazing angle or on a needle whose plane is
        // ill-conditioned, the float t stays: it is consistent with the edge test (a convex
        // combination of the corners' z). Either way the hit point lies on its triangle up to
        // rounding, so every accelerator holding the triangle finds the same closest hit.
        // Barycentrics of the crossing x = b1 e1 + b2 e2 (relative to p0), times |n|^2:
        // (x x e2).n = b1 |n|^2 and (e1 x x).n = b2 |n|^2.
        const double x[3] = {te * r.d[0] - w[0], te * r.d[1] - w[1], te * r.d[2] - w[2]};
        const double nn = nx * nx + ny * ny + nz * nz, tol = 0x1p-24 * nn;
        const double s1 = (x[1] * e2[2] - x[2] * e2[1]) * nx + (x[2] * e2[0] - x[0] * e2[2]) * ny + (x[0] * e2[1] - x[1] * e2[0]) * nz;
        const double s2 = (e1[1] * x[2] - e1[2] * x[1]) * nx + (e1[2] * x[0] - e1[0] * x[2]) * ny + (e1[0] * x[1] - e1[1] * x[0]) * nz;
        if (s1 >= -tol && s2 >= -tol && nn - s1 - s2 >= -tol) out = withLane(out, j, signedFloat(te));
    }
    return out;
}

/// Möller & Trumbore 1997: Cramer's rule on [-d, e1, e2] (t, u, v) = o - p0, with the edges
/// e1 = p1 - p0, e2 = p2 - p0 rounded to float in the kernel. Known leaks: u, v and u + v are
/// rounded independently for the two triangles of a shared edge, so a ray through (or within a
/// few ulps of) the edge can miss both; tests/accel/test_triangle_decisions.cpp measures how
/// often.
///
/// t's rounding error grows like u |e1| |e2| |d| / |det| (the shape of the triangle over the
/// sine of the ray's angle to it: large on slivers, where det and e2.q are cross products of
/// nearly parallel edges) times (|o - p0| + t |d|). Where that first-order estimate (with a
/// factor 2 of margin) exceeds 2^-19 of the problem's scale (needsExactT), t is recomputed
/// from the plane equation in double (exactPlaneT): the remedy of computing the
/// distance from the plane where the edge-based t is ill-conditioned, only where it is.
template <int L, bool kAnyHit = false>
[[gnu::always_inline]] inline Step<L> mollerTrumbore(const TriangleRay &r, const float *rows, uint32_t n, uint32_t i, VMask<L> m, float maxt,
                                                     uint32_t skipPrim) {
    using F = VFloat<L>;
    const F dx = r.d[0], dy = r.d[1], dz = r.d[2];
    const F p0x = loadRow(rows, n, 0, i, m), p0y = loadRow(rows, n, 1, i, m), p0z = loadRow(rows, n, 2, i, m);
    const F e1x = loadRow(rows, n, 3, i, m) - p0x, e1y = loadRow(rows, n, 4, i, m) - p0y, e1z = loadRow(rows, n, 5, i, m) - p0z;
    const F e2x = loadRow(rows, n, 6, i, m) - p0x, e2y = loadRow(rows, n, 7, i, m) - p0y, e2z = loadRow(rows, n, 8, i, m) - p0z;
    F px = dy * e2z - dz * e2y;
    F py = dz * e2x - dx * e2z;
    F pz = dx * e2y - dy * e2x;
    F det = e1x * px + e1y * py + e1z * pz;
    VMask<L> valid = m & (det != 0.0f);
    F invDet = F(1.0f) / det;
    F tx = F(r.o[0]) - p0x;
    F ty = F(r.o[1]) - p0y;
    F tz = F(r.o[2]) - p0z;
    F u = (tx * px + ty * py + tz * pz) * invDet;
    // Reject u < 0 or u > 1 (ordered compares: a NaN is rejected by the t test below).
    valid = valid & ~((u < 0.0f) | (u > 1.0f));
    if (!any(valid)) return {u, u, u, valid};  // most steps: every lane fails already
    F qx = ty * e1z - tz * e1y;
    F qy = tz * e1x - tx * e1z;
    F qz = tx * e1y - ty * e1x;
    F v = (dx * qx + dy * qy + dz * qz) * invDet;
    valid = valid & ~((v < 0.0f) | (u + v > 1.0f));
    F t = (e2x * qx + e2y * qy + e2z * qz) * invDet;
    VMask<L> known{};
    NORI_TRIANGLE_COUNT(stepsInside, any(valid));
    if (any(valid)) {
        const F e1 = max(max(abs(e1x), abs(e1y)), abs(e1z)), e2 = max(max(abs(e2x), abs(e2y)), abs(e2z));
        const F w = max(max(abs(tx), abs(ty)), abs(tz));
        const TScale sc(r);
        const F err = F(0x1p-23f) * (e1 * e2 * F(sc.dInf) * abs(invDet)) * (w * F(sc.rcpDInf) + abs(t));
        const VMask<L> redo = needsExactT(valid, t, err, sc.oScale, r.mint, maxt);
        if (any(redo)) {
            // Rounding error bound of u, v and 1 - u - v against the exact barycentrics (inf
            // norms D = |d|, E = max |e1|, |e2|, |o - p0|): e1, e2, o - p0 rounded once, p, q and
            // the dot products then add at most 110u D E (|o - p0| + E) / |det| + 6u, and
            // D E^2 / |det| >= 1/6. Lanes clear of that bound by a factor 3.5 surely cross
            // inside the triangle.
            const F e = max(e1, e2);
            const F bound = F(0x1p-15f) * (F(sc.dInf) * e) * (w + e) * abs(invDet);
            const VMask<L> inside = (u > bound) & (v > bound) & (F(1.0f) - (u + v) > bound);
            if constexpr (kAnyHit) {
                const VMask<L> sure = surelyInRange(valid & inside, t, err, r.mint, maxt);
                if (any(sure)) return {t, u, v, sure};
            }
            t = exactPlaneT(redo, inside, r, rows, n, i, t, skipPrim);
            known = redo & inside;
        }
    }
    valid = valid & (t >= r.mint) & (t <= maxt);
    return {t, u, v, valid, known};
}

/// Edge functions of one watertight step.
template <int L>
struct Edges {
    VFloat<L> U, V, W;
    /// From exactEdges: the lanes whose exact volumes are all nonzero with one sign (the real ray
    /// crosses strictly inside the triangle), and those whose exact decision overturned the
    /// float one (their U, V, W are the exact volumes, scaled).
    VMask<L> strict{}, overturned{};
};

/// The lanes of \p redo whose exact decision (exactEdgeVolumes: exact signs of the real ray's and
/// triangle's edge volumes) differs from the float one get those volumes as their edge functions,
/// scaled to at most 1 in magnitude; a nonzero value too small for a float keeps its sign. The
/// other lanes keep \p e's, so t and u, v stay bit for bit where the decision does not change.
/// A lane with a non-finite input gets mixed signs (a miss). A float or exact decision is a hit
/// where the three values have no mixed signs (zero counts as either), except that three exact
/// zeros are a miss: the ray lies in the triangle's plane, whatever signs the float rounding
/// noise had. Both returned masks lie within \p redo. Out of line: only rays within the float
/// edge functions' rounding error of an edge get here (all rays near the edges of a triangle far
/// larger than their distance to it: a ground quad's diagonal under a small object).
template <int L>
[[gnu::noinline]] Edges<L> exactEdges(VMask<L> redo, const TriangleRay &r, const float *rows, uint32_t n, uint32_t i,
                                                 Edges<L> e) {
    float u[L], v[L], w[L], strict[L] = {}, overturned[L] = {};
    e.U.storeu(u);
    e.V.storeu(v);
    e.W.storeu(w);
    for (unsigned b = bits(redo); b; b &= b - 1) {
        const int j = __builtin_ctz(b);
        float p[3][3];
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) p[c][k] = rows[size_t(3 * c + k) * n + i + uint32_t(j)];
        double vol[3];
        const bool floatHit = !((u[j] < 0.0f || v[j] < 0.0f || w[j] < 0.0f) && (u[j] > 0.0f || v[j] > 0.0f || w[j] > 0.0f));
        if (!exactEdgeVolumes(r.o, r.d, p, vol)) {
            u[j] = 1.0f, v[j] = -1.0f, w[j] = 0.0f;
            overturned[j] = floatHit ? 1.0f : 0.0f;
            continue;
        }
        const bool exactHit = !((vol[0] < 0.0 || vol[1] < 0.0 || vol[2] < 0.0) && (vol[0] > 0.0 || vol[1] > 0.0 || vol[2] > 0.0)) &&
                              (vol[0] != 0.0 || vol[1] != 0.0 || vol[2] != 0.0);
        if (exactHit && vol[0] != 0.0 && vol[1] != 0.0 && vol[2] != 0.0) strict[j] = 1.0f;
        // Where the exact decision is the float one (most lanes), the float values stay: no
        // need to scale these (three divisions).
        if (floatHit == exactHit) continue;
        overturned[j] = 1.0f;
        const double scale = std::max({std::abs(vol[0]), std::abs(vol[1]), std::abs(vol[2])});
        if (scale > 0.0) vol[0] /= scale, vol[1] /= scale, vol[2] /= scale;
        u[j] = signedFloat(vol[0]);
        v[j] = signedFloat(vol[1]);
        w[j] = signedFloat(vol[2]);
    }
    return {VFloat<L>::loadu(u), VFloat<L>::loadu(v), VFloat<L>::loadu(w), VFloat<L>::loadu(strict) != 0.0f,
            VFloat<L>::loadu(overturned) != 0.0f};
}

/// Lanes whose three edge functions have mixed signs (zero counts as either sign): a miss.
template <int L>
[[gnu::always_inline]] inline VMask<L> mixedSigns(VFloat<L> U, VFloat<L> V, VFloat<L> W) {
    return ((U < 0.0f) | (V < 0.0f) | (W < 0.0f)) & ((U > 0.0f) | (V > 0.0f) | (W > 0.0f));
}

/// Woop, Benthin & Wald 2013 (JCGT 2(1)) on rows p0, p1, p2: vertices relative to the origin,
/// sheared so that the ray is the +z axis, then 2D edge functions; both windings hit.
///
/// The decision is exact for the real ray and triangle, not only for the rounded sheared corners
/// (the paper's guarantee): a sheared coordinate is a difference of two rounded terms, and where
/// they cancel (an axis-aligned box edge seen along its face) it rounds to 0 or past it, so the
/// paper's exact signs of the rounded corners put a ray up to ~1e-7 of the scale on the wrong
/// side of an edge: hits on a box's silhouette it passes beside, misses of a grass blade it
/// crosses. Each float edge function is within 16u M (M + Z) of the exact one (M = the largest
/// sheared |x|, |y|, Z = the largest |z| before scaling, u = 2^-24; see below); lanes whose signs
/// that bound settles are decided in float, the others by exactEdges (exact signs of the real
/// edge volumes): a ray through a shared edge still hits one of its two triangles, and both
/// exactly when it meets the edge's line.
///
/// t = sum E_i z_i / sum E_i comes from the same sheared corners, whose rounding errors scale
/// with their distance |p - o| from the ray origin, not with t: on a triangle much larger than the
/// hit distance (a 2000-unit ground seen from 6 units) t is off by more than the distance to the
/// plane, and a ray leaving the surface re-hits it. Those lanes, and the lanes whose exact
/// decision overturned the float one, get t from the plane equation in double (exactPlaneT).
template <int L, bool kAnyHit = false>
[[gnu::always_inline]] inline Step<L> watertight(const TriangleRay &r, const float *rows, uint32_t n, uint32_t i, VMask<L> m, float maxt,
                                                 uint32_t skipPrim) {
    using F = VFloat<L>;
    const F ox = r.o[r.kx], oy = r.o[r.ky], oz = r.o[r.kz], sx = r.sx, sy = r.sy, sz = r.sz;
    // The ray's axes' rows of p0 (those of p1 and p2 lie 3n and 6n further): three products
    // for the nine row addresses, not one per row.
    const size_t s3 = size_t(3) * n;
    const float *X = rows + size_t(r.kx) * n + i, *Y = rows + size_t(r.ky) * n + i, *Zr = rows + size_t(r.kz) * n + i;
    F az = F::load(Zr, m) - oz;
    F bz = F::load(Zr + s3, m) - oz;
    F cz = F::load(Zr + 2 * s3, m) - oz;
    // Sheared corners.
    const F ax = (F::load(X, m) - ox) - sx * az, ay = (F::load(Y, m) - oy) - sy * az;
    const F bx = (F::load(X + s3, m) - ox) - sx * bz, by = (F::load(Y + s3, m) - oy) - sy * bz;
    const F cx = (F::load(X + 2 * s3, m) - ox) - sx * cz, cy = (F::load(Y + 2 * s3, m) - oy) - sy * cz;
    // Scaled barycentrics: U weighs p0, V weighs p1, W weighs p2.
    F U = cx * by - cy * bx;
    F V = ax * cy - ay * cx;
    F W = bx * ay - by * ax;
    // Error bound. A sheared coordinate x = fl(fl(p - o) - fl(fl(sx) fl(p_z - o_z))) is off the
    // exact one (exact shear of the real ray) by at most u (|p - o| + 3 |sx z| + |x|) <=
    // u (2M + 4Z) (|sx|, |sy| <= 1), so U = fl(fl(cx by) - fl(cy bx)) by at most
    // 4M u (2M + 4Z) + 4u M^2 <= 16u M (M + Z). The exact U, V, W of the real ray are its edge
    // volumes over d[kz], one sign for all three. The bound below is twice that (room for its
    // own rounding, a few u, and the second-order terms), plus 2^-125 for underflow (products and
    // shears of coordinates near 2^-126). (It was 4x until round 39: the lanes it leaves unsure
    // go to exactEdges, and halving it halves them near the edges of huge triangles. A bound of
    // 2^-25 M (M + Z) fails TriangleDecisions.*, Watertight.* and KernelPrecision.* tests.)
    // (maxAbs: one instruction with AVX-512.)
    const F M = max(max(maxAbs(ax, ay), maxAbs(bx, by)), maxAbs(cx, cy)), Z = max(maxAbs(az, bz), abs(cz));
    const F bound = F(0x1p-19f) * M * (M + Z) + F(0x1p-125f);
    const F negBound = F(0.0f) - bound;
    // Surely missed: signs surely mixed, i.e. the largest edge function above the bound and the
    // smallest below minus it (four min/max and two compares instead of six compares and four
    // ors: this test runs on every step). A NaN edge function drops out of the min/max (or
    // hides the one before it): such a lane is not surely missed and the tests below decide it.
    const F hi = max(max(U, V), W), lo = min(min(U, V), W);
    VMask<L> valid = m & ~((hi > bound) & (lo < negBound));
    if (!any(valid)) return {U, V, W, valid};  // most steps: the ray passes beside every triangle
    // Surely hit (crossing strictly inside): three signs surely equal, i.e. the smallest edge
    // function above the bound or the largest below minus it, where none is a NaN (their sum is
    // a NaN then, and also where they hold both infinities: mixed signs). The rest: exact signs.
    F det = U + V + W;
    const VMask<L> inside = ((lo > bound) | (hi < negBound)) & (det == det);
    const VMask<L> unsure = valid & ~inside;
    // The unsure lanes whose exact decision differs from the float signs' take the exact
    // volumes (exactEdges; exactly: those lanes). strict: the lanes known to cross strictly
    // inside the triangle, surely by the float edge functions or by exact volumes that are all
    // nonzero.
    VMask<L> strict = inside, exactly{};
    if (__builtin_expect(any(unsure), 0)) {  // (rare: kept out of the hot path's registers and code)
        const Edges<L> e = exactEdges(unsure, r, rows, n, i, Edges<L>{U, V, W});
        // Lanes whose exact volumes have no zero cross strictly inside, whether or not that
        // overturned the float decision; those with a zero one cross on an edge, and
        // exactPlaneT's inside test keeps them. (Before round 39 only the overturned lanes
        // counted: every ray near a huge ground quad's diagonal took the general plane and
        // inside test instead of the axis-aligned plane's one division.)
        strict = strict | e.strict;
        exactly = e.overturned;
        U = e.U, V = e.V, W = e.W;
        valid = m & ~mixedSigns(U, V, W);
        if (!any(valid)) return {U, V, W, valid};
        det = U + V + W;
    }
    valid = valid & (det != 0.0f);
    NORI_TRIANGLE_COUNT(stepsInside, any(valid));
    const F za = sz * az, zb = sz * bz, zc = sz * cz;
    F T = U * za + V * zb + W * zc;
    F invDet = F(1.0f) / det;
    F t = T * invDet;
    VMask<L> known{};
    // t's error, first order, in units of |d|_inf (with a factor 4 of margin): the sheared
    // corners carry absolute errors of a few u times their magnitudes (u (|x, y|_max +
    // 2 |z|_max)), and the rounding of the edge functions moves the point they weigh by up to
    // ~6u M^3 / |det| across the triangle (M = |x, y|_max), which the plane's slope turns into an
    // error off the plane of the same size: large on slivers and grazing rays. Beyond 2^-19 of
    // the problem's scale (needsExactT), i.e. on triangles much larger than their distance to
    // the origin and on slivers, t comes from the plane equation in double instead; so does t of
    // every lane the exact decision overturned (its U, V, W are exact volumes, not the corners').
    if (any(valid)) {
        const TScale sc(r);
        // max |sz z_i| = |sz| max |z_i|, the same bits (rounding is monotonic and symmetric). Z
        // (maxAbs) may drop a NaN at some widths, but a NaN z makes t a NaN, which needs the
        // double t whatever err is.
        const F zmax = F(sc.rcpDInf) * Z;
        const F shape = M * M * M * abs(invDet);
        const F err = F(0x1p-22f) * ((M + F(4.0f) * shape) * F(sc.rcpDInf) + F(2.0f) * zmax);
        VMask<L> redo = needsExactT(valid, t, err, sc.oScale, r.mint, maxt) | (valid & exactly);
        if (any(redo)) {
            // (Only the lanes the float edge functions decided: the estimate err does not hold
            // for a crossing within their rounding of an edge, nor for the lanes decided exactly,
            // whose t is not the corners'.)
            if constexpr (kAnyHit) {
                const VMask<L> sure = surelyInRange(valid & inside, t, err, r.mint, maxt);
                if (any(sure)) return {t, V * invDet, W * invDet, sure};
            }
            // A triangle square to the ray's dominant axis (its corners' z equal: a wall faced,
            // a floor seen from above) keeps its float t, whatever the estimate says: t is then z
            // at any weights, and the weights of a lane not surely missed have one sign, so
            // fl(fl(sum U_i z) / fl(sum U_i)) lies within a few u of z, itself within 2u of the
            // exact distance. (Not the lanes decided exactly: their U, V, W are not the corners'.)
            redo = redo & ~((az == bz) & (az == cz) & ~exactly);
            if (any(redo)) {
                t = exactPlaneT(redo, strict, r, rows, n, i, t, skipPrim);
                known = redo & strict;
            }
        }
    }
    valid = valid & (t >= r.mint) & (t <= maxt);
    return {t, V * invDet, W * invDet, valid, known};
}

/// \p s, counted in a measuring build as a kernel step (with a hit, if it has one).
template <int L>
[[gnu::always_inline]] inline Step<L> counted(Step<L> s) {
#ifdef NORI_OCTREE_COUNTERS
    g_octreeCounters.steps += 1;
    g_octreeCounters.stepsHit += any(s.hit);
#endif
    return s;
}

/// One step of the chosen kernel. With \p kAnyHit (an occlusion query) the step may stop at
/// the first lanes surely hit, and then reports only those.
template <int L, bool kAnyHit = false>
[[gnu::always_inline]] inline Step<L> testStep(Intersector kind, const TriangleRay &r, const float *rows, uint32_t n, uint32_t i,
                                               uint32_t end, float maxt, uint32_t skipPrim = ~0u) {
    const VMask<L> m = VMask<L>::firstN(end - i);
    return counted(kind == Intersector::MT ? mollerTrumbore<L, kAnyHit>(r, rows, n, i, m, maxt, skipPrim)
                                           : watertight<L, kAnyHit>(r, rows, n, i, m, maxt, skipPrim));
}

/// Whether triangles [first, end) of a leaf (a small leaf or kept list, a leaf's tail, one
/// block) are at most eight: in a 16-lane build they take one 8-lane step instead, half the
/// micro-operations of a 16-lane one, with the same answers bit for bit.
template <int L>
inline bool narrowSpan(uint32_t first, uint32_t end) {
#if NORI_LANES_AVX2
    if constexpr (L > 8) return end - first <= 8;
#endif
    (void)first, (void)end;
    return false;
}

/// Closest hit over triangles [first, end) of a leaf (at most 16) in steps of L lanes: the
/// lexicographic minimum of (t, prim), so ties resolve the same way at every width.
template <int L, Intersector kKind>
bool spanSteps(const TriangleRay &ray, const float *rows, uint32_t n, uint32_t first, uint32_t end, Hit &best) {
    bool found = false;
    NORI_TRIANGLE_COUNT(chunks, 1);
    for (uint32_t i = first; i < end; i += L) {
        Step<L> s = testStep<L>(kKind, ray, rows, n, i, end, best.t, best.prim);
        if (!any(s.hit)) continue;
        const unsigned hits = bits(s.hit);
        float tmin;
        int winner = -1;
        uint32_t prim = ~0u;
        if (!(hits & (hits - 1))) {  // one lane (most steps with a hit): no reduction
            winner = __builtin_ctz(hits);
            tmin = lane(s.t, winner);
            prim = primAt(rows, n, i + uint32_t(winner));
        } else {
            tmin = reduceMin(s.hit, s.t);
            for (unsigned b = bits(s.hit & (s.t == tmin)); b; b &= b - 1) {
                const int j = __builtin_ctz(b);
                const uint32_t p = primAt(rows, n, i + uint32_t(j));
                if (p < prim) prim = p, winner = j;
            }
        }
        if (tmin < best.t || (tmin == best.t && prim < best.prim)) {
            best = Hit{tmin, lane(s.u, winner), lane(s.v, winner), prim};
            found = true;
        }
    }
    return found;
}

/// spanSteps() at L lanes, or at 8 where narrowSpan() says so. Decided in the caller (inline):
/// inside the step loop's function the test came after its prologue, and a narrow span paid a
/// second call with a second prologue (a large stack frame, aligned for the vector spills).
template <int L>
[[gnu::always_inline]] inline bool spanIntersect(Intersector kind, const TriangleRay &ray, const float *rows, uint32_t n,
                                                 uint32_t first, uint32_t end, Hit &best) {
    // (The kernel chosen here, once per span, not in every step.)
    constexpr Intersector mt = Intersector::MT, wt = Intersector::Watertight;
    if constexpr (L > 8)
        if (narrowSpan<L>(first, end))
            return kind == mt ? spanSteps<8, mt>(ray, rows, n, first, end, best) : spanSteps<8, wt>(ray, rows, n, first, end, best);
    return kind == mt ? spanSteps<L, mt>(ray, rows, n, first, end, best) : spanSteps<L, wt>(ray, rows, n, first, end, best);
}

/// Entry distances of the ray into block boxes 16g .. 16g + 15 of a leaf (tn[j] for block
/// 16g + j); bit j of the result is set when that block is entered within [ray.mint, maxt].
/// The conservative slab test of the octree nodes; a NaN never narrows the interval.
template <int L>
[[gnu::always_inline]] inline unsigned blockEntries(const TriangleRay &r, const float *rows, uint32_t n, uint32_t nb,
                                                    uint32_t g, float maxt, float tn[16]) {
    using F = VFloat<L>;
    const float *boxes = rows + size_t(10) * n;
    // The ray's rows and constants in locals, once: read through \p r in the loop, they were
    // read again (and the row addresses multiplied out again) after every store to \p tn,
    // which might alias them: 89 instructions per block of L boxes instead of about 45.
    const float *nearRow[3], *farRow[3];
    F o[3], rcpNear[3], rcpFar[3];
    for (int a = 0; a < 3; ++a) {
        const float *lower = boxes + size_t(a) * nb, *upper = lower + size_t(3) * nb;
        nearRow[a] = r.neg[a] ? upper : lower;
        farRow[a] = r.neg[a] ? lower : upper;
        o[a] = F(r.o[a]);
        rcpNear[a] = F(r.rcpNear[a]);
        rcpFar[a] = F(r.rcpFar[a]);
    }
    const F mint(r.mint), limit(maxt);
    unsigned mask = 0;
    for (uint32_t k = 16 * g; k < std::min(nb, 16 * g + 16); k += L) {
        const VMask<L> m = VMask<L>::firstN(nb - k);
        F t0 = mint, t1 = limit;
        for (int a = 0; a < 3; ++a) {
            F nearPlane = F::load(nearRow[a] + k, m);
            F farPlane = F::load(farRow[a] + k, m);
            t0 = max((nearPlane - o[a]) * rcpNear[a], t0);
            t1 = min((farPlane - o[a]) * rcpFar[a], t1);
        }
        t0.storeu(tn + (k - 16 * g));
        mask |= bits(m & (t0 <= t1)) << (k - 16 * g);
    }
    return mask;
}

/// The triangles of block k (of a leaf above 16) to test together: the block's own, or for
/// blocks of 8 its pair's too (blocks 2j and 2j + 1, one aligned run of 16) when \p both: for a
/// 16-lane kernel, one step for both costs no more than two half steps. At every width, so that
/// every width visits the same triangles in the same order (the choice between float and
/// double t depends on the closest hit so far: see needsExactT). Clears what it takes from
/// \p mask.
inline void blockSpan(uint32_t n, uint32_t g, int k, bool both, unsigned &mask, uint32_t &first, uint32_t &end) {
    const uint32_t size = TriangleStore::blockSize(n);
    mask &= ~(1u << k);
    first = (16 * g + uint32_t(k)) << TriangleStore::blockShift(n);
    if (size == 8 && both) {
        mask &= ~(1u << (k ^ 1));
        first &= ~15u;
        end = std::min(n, first + 16);
    } else {
        end = std::min(n, first + size);
    }
}

/// Closest hit in a leaf: blocks in order of entry distance (ties: lower index), skipping those
/// entered beyond the closest hit so far.
template <int L>
bool leafIntersect(Intersector kind, const TriangleRay &ray, const float *rows, uint32_t n, Hit &best) {
    if (n <= 16) return spanIntersect<L>(kind, ray, rows, n, 0, n, best);
    bool found = false;
    const uint32_t nb = TriangleStore::blockCount(n);
    for (uint32_t g = 0; 16 * g < nb; ++g) {
        float tn[16];
        unsigned mask = blockEntries<L>(ray, rows, n, nb, g, ray.cullLimit(best.t), tn);
        while (mask) {
            // The nearest block left (the running minimum kept in a register, not reloaded).
            int k = __builtin_ctz(mask);
            float tk = tn[k];
            for (unsigned b = mask & (mask - 1); b; b &= b - 1) {
                const int j = __builtin_ctz(b);
                const float tj = tn[j];
                if (tj < tk) k = j, tk = tj;
            }
            const float limit = ray.cullLimit(best.t);
            if (tk > limit) break;
            uint32_t first, end;
            blockSpan(n, g, k, (mask >> (k ^ 1) & 1u) && tn[k ^ 1] <= limit, mask, first, end);
            found |= spanIntersect<L>(kind, ray, rows, n, first, end, best);
        }
    }
    return found;
}

/// Any hit among triangles [first, end) (at most 16) with t in [ray.mint, maxt], in steps of L
/// lanes.
template <int L, Intersector kKind>
bool occludedSteps(const TriangleRay &ray, const float *rows, uint32_t n, uint32_t first, uint32_t end, float maxt) {
    NORI_TRIANGLE_COUNT(chunks, 1);
    for (uint32_t i = first; i < end; i += L)
        if (any(testStep<L, true>(kKind, ray, rows, n, i, end, maxt).hit)) return true;
    return false;
}

/// occludedSteps() at L lanes, or at 8 where narrowSpan() says so (as spanIntersect()).
template <int L>
[[gnu::always_inline]] inline bool spanOccluded(Intersector kind, const TriangleRay &ray, const float *rows, uint32_t n,
                                                uint32_t first, uint32_t end, float maxt) {
    constexpr Intersector mt = Intersector::MT, wt = Intersector::Watertight;
    if constexpr (L > 8)
        if (narrowSpan<L>(first, end))
            return kind == mt ? occludedSteps<8, mt>(ray, rows, n, first, end, maxt) : occludedSteps<8, wt>(ray, rows, n, first, end, maxt);
    return kind == mt ? occludedSteps<L, mt>(ray, rows, n, first, end, maxt) : occludedSteps<L, wt>(ray, rows, n, first, end, maxt);
}

/// Any hit in the leaf with t in [ray.mint, maxt].
template <int L>
bool leafOccluded(Intersector kind, const TriangleRay &ray, const float *rows, uint32_t n, float maxt) {
    if (n <= 16) return spanOccluded<L>(kind, ray, rows, n, 0, n, maxt);
    const uint32_t nb = TriangleStore::blockCount(n);
    for (uint32_t g = 0; 16 * g < nb; ++g) {
        float tn[16];
        unsigned mask = blockEntries<L>(ray, rows, n, nb, g, maxt, tn);
        while (mask) {
            const int k = __builtin_ctz(mask);
            uint32_t first, end;
            blockSpan(n, g, k, mask >> (k ^ 1) & 1u, mask, first, end);
            if (spanOccluded<L>(kind, ray, rows, n, first, end, maxt)) return true;
        }
    }
    return false;
}

/// Every triangle's own answer in chunk k, without the closest-hit reduction.
template <int L>
unsigned chunkDecisions(Intersector kind, const TriangleRay &ray, const float *rows, uint32_t n, uint32_t k,
                        float maxt, TriangleStore::ChunkAnswers &out) {
    unsigned hits = 0, known = 0;
    const uint32_t end = std::min(n, 16 * k + 16);
    for (uint32_t i = 16 * k; i < end; i += L) {
        Step<L> s = testStep<L>(kind, ray, rows, n, i, end, maxt);
        float t[L], u[L], v[L];
        s.t.storeu(t);
        s.u.storeu(u);
        s.v.storeu(v);
        for (int j = 0; j < L && i + uint32_t(j) < std::min(n, 16 * k + 16); ++j) {
            const uint32_t slot = i + uint32_t(j) - 16 * k;
            out.t[slot] = t[j], out.u[slot] = u[j], out.v[slot] = v[j];
        }
        hits |= bits(s.hit) << (i - 16 * k);
        known |= bits(s.known & VMask<L>::firstN(std::min(n, 16 * k + 16) - i)) << (i - 16 * k);
    }
    out.insideKnown = known;
    return out.hits = hits;
}

/// Call \p f with std::integral_constant<int, L> for a lane count of this build.
template <typename Fn>
auto withLanes(int lanes, Fn &&f) {
    switch (lanes) {
#if NORI_LANES_AVX512
    case 16: return f(std::integral_constant<int, 16>());
#endif
#if NORI_LANES_AVX2
    case 8: return f(std::integral_constant<int, 8>());
#endif
    case 1: return f(std::integral_constant<int, 1>());
    default: throw std::invalid_argument(fmt::format("TriangleStore: {} lanes are not compiled into this build", lanes));
    }
}

} // namespace

std::vector<int> TriangleStore::laneWidths() {
    std::vector<int> widths;
    for (int l : {16, 8, 1})
        if (lanes::available(l)) widths.push_back(l);
    return widths;
}

bool TriangleStore::intersect(const TriangleRay &ray, size_t offset, uint32_t n, Hit &best) const {
    return leafIntersect<kMaxLanes>(m_kind, ray, m_data.data() + offset, n, best);
}

bool TriangleStore::occluded(const TriangleRay &ray, size_t offset, uint32_t n, float maxt) const {
    return leafOccluded<kMaxLanes>(m_kind, ray, m_data.data() + offset, n, maxt);
}

bool TriangleStore::intersectReference(const TriangleRay &ray, size_t offset, uint32_t n, Hit &best) const {
    return leafIntersect<1>(m_kind, ray, m_data.data() + offset, n, best);
}

bool TriangleStore::intersectLanes(int lanes, const TriangleRay &ray, size_t offset, uint32_t n, Hit &best) const {
    return withLanes(lanes, [&](auto l) { return leafIntersect<l()>(m_kind, ray, m_data.data() + offset, n, best); });
}

bool TriangleStore::occludedLanes(int lanes, const TriangleRay &ray, size_t offset, uint32_t n, float maxt) const {
    return withLanes(lanes, [&](auto l) { return leafOccluded<l()>(m_kind, ray, m_data.data() + offset, n, maxt); });
}

unsigned TriangleStore::chunkAnswers(int lanes, const TriangleRay &ray, size_t offset, uint32_t n, uint32_t k,
                                     float maxt, ChunkAnswers &out) const {
    return withLanes(lanes, [&](auto l) { return chunkDecisions<l()>(m_kind, ray, m_data.data() + offset, n, k, maxt, out); });
}

} // namespace nori
