/// \file triangle.cpp
/// \brief Ray/triangle intersectors and the leaf triangle store.
/// No FMA contraction in this file: see triangle.h for why results must be bit-reproducible.
#pragma GCC optimize("fp-contract=off")
// GCC 12's _mm512_max_ps / _mm512_min_ps expand to _mm512_undefined_ps(), which -Wuninitialized
// reports once inlined here; the value is never read.
#pragma GCC diagnostic ignored "-Wuninitialized"

#include "triangle.h"
#include <cmath>
#include <algorithm>
#include <cstring>

// Widest kernels the compiler may use: sixteen lanes with AVX-512, eight with AVX2, else scalar.
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512DQ__)
#include <immintrin.h>
#define NORI_TRIANGLE_AVX512 1
#elif defined(__AVX2__)
#include <immintrin.h>
#define NORI_TRIANGLE_AVX2 1
#endif

namespace nori {

Intersector parseIntersector(const PropertyList &props, const std::string &defaultValue) {
    std::string name = props.getString("intersector", defaultValue);
    if (name == "mt") return Intersector::MT;
    if (name == "watertight") return Intersector::Watertight;
    props.fail("intersector", fmt::format("unknown intersector '{}' (allowed: mt, watertight)", name));
}

const char *intersectorName(Intersector kind) { return kind == Intersector::MT ? "mt" : "watertight"; }

TriangleRay::TriangleRay(const Ray3f &ray) {
    for (int i = 0; i < 3; ++i) {
        o[i] = ray.o[i];
        d[i] = ray.d[i];
    }
    mint = ray.mint;
    // Woop et al. 2013, section 3: shear/scale so that the ray becomes the +z axis.
    float ax = std::abs(d[0]), ay = std::abs(d[1]), az = std::abs(d[2]);
    kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    kx = kz == 2 ? 0 : kz + 1;
    ky = kx == 2 ? 0 : kx + 1;
    if (d[kz] < 0.0f) std::swap(kx, ky);
    sx = d[kx] / d[kz];
    sy = d[ky] / d[kz];
    sz = 1.0f / d[kz];
    for (int a = 0; a < 3; ++a) {
        neg[a] = std::signbit(ray.d[a]) ? 1 : 0;
        rcpNear[a] = ray.dRcp[a] * (1.0f - 0x1p-20f);
        rcpFar[a] = ray.dRcp[a] * (1.0f + 0x1p-20f);
    }
}

// ---------------------------------------------------------------------------------------------
// Scalar kernels. The SIMD kernels below perform the same IEEE operations in the same order.

bool intersectMT(const TriangleRay &r, const float v0[3], const float e1[3], const float e2[3], float maxt,
                 float &t, float &u, float &v) {
    // Möller & Trumbore 1997: Cramer's rule on [-d, e1, e2] (t, u, v) = o - v0.
    float px = r.d[1] * e2[2] - r.d[2] * e2[1];
    float py = r.d[2] * e2[0] - r.d[0] * e2[2];
    float pz = r.d[0] * e2[1] - r.d[1] * e2[0];
    float det = e1[0] * px + e1[1] * py + e1[2] * pz;
    if (det == 0.0f) return false;
    float invDet = 1.0f / det;
    float tx = r.o[0] - v0[0], ty = r.o[1] - v0[1], tz = r.o[2] - v0[2];
    u = (tx * px + ty * py + tz * pz) * invDet;
    if (u < 0.0f || u > 1.0f) return false;
    float qx = ty * e1[2] - tz * e1[1];
    float qy = tz * e1[0] - tx * e1[2];
    float qz = tx * e1[1] - ty * e1[0];
    v = (r.d[0] * qx + r.d[1] * qy + r.d[2] * qz) * invDet;
    if (v < 0.0f || u + v > 1.0f) return false;
    t = (e2[0] * qx + e2[1] * qy + e2[2] * qz) * invDet;
    return t >= r.mint && t <= maxt;
}

namespace {
/// Edge functions in double precision: the products of floats are exact, so the sign is right
/// even when the float evaluation cancels to zero (Woop et al. 2013, section 4).
void edgeFunctionsDouble(float ax, float ay, float bx, float by, float cx, float cy, float &U, float &V, float &W) {
    U = float(double(cx) * double(by) - double(cy) * double(bx));
    V = float(double(ax) * double(cy) - double(ay) * double(cx));
    W = float(double(bx) * double(ay) - double(by) * double(ax));
}
} // namespace

bool intersectWatertight(const TriangleRay &r, const float p0[3], const float p1[3], const float p2[3], float maxt,
                         float &t, float &u, float &v) {
    // Vertices relative to the origin, then sheared so that the ray is the +z axis.
    float az0 = p0[r.kz] - r.o[r.kz], bz0 = p1[r.kz] - r.o[r.kz], cz0 = p2[r.kz] - r.o[r.kz];
    float ax = (p0[r.kx] - r.o[r.kx]) - r.sx * az0, ay = (p0[r.ky] - r.o[r.ky]) - r.sy * az0;
    float bx = (p1[r.kx] - r.o[r.kx]) - r.sx * bz0, by = (p1[r.ky] - r.o[r.ky]) - r.sy * bz0;
    float cx = (p2[r.kx] - r.o[r.kx]) - r.sx * cz0, cy = (p2[r.ky] - r.o[r.ky]) - r.sy * cz0;
    // Scaled barycentrics: U weighs p0, V weighs p1, W weighs p2.
    float U = cx * by - cy * bx;
    float V = ax * cy - ay * cx;
    float W = bx * ay - by * ax;
    if (U == 0.0f || V == 0.0f || W == 0.0f) edgeFunctionsDouble(ax, ay, bx, by, cx, cy, U, V, W);
    // Both windings are hits: the three must not have mixed signs.
    if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return false;
    float det = U + V + W;
    if (det == 0.0f) return false;
    float T = U * (r.sz * az0) + V * (r.sz * bz0) + W * (r.sz * cz0);
    float invDet = 1.0f / det;
    t = T * invDet;
    if (!(t >= r.mint && t <= maxt)) return false;
    u = V * invDet;
    v = W * invDet;
    return true;
}

// ---------------------------------------------------------------------------------------------

void TriangleStore::reset(Intersector kind, size_t words) {
    m_kind = kind;
    m_data.assign(words, 0.0f);
    m_data.shrink_to_fit();
}

namespace {
struct Keyed {
    Point3f centroid;  ///< three times the centroid: only its order matters
    uint32_t prim;
};

/// Order [begin, end) so that every aligned run of 16 is spatially compact: split at a
/// multiple of 16 along the longest axis of the centroids, recursively (a median split as in
/// a BVH's bottom levels).
void orderChunks(Keyed *items, uint32_t begin, uint32_t end) {
    if (end - begin <= 16) return;
    BoundingBox3f box;
    for (uint32_t i = begin; i < end; ++i) box.expandBy(items[i].centroid);
    int axis = box.majorAxis();
    uint32_t chunks = (end - begin + 15) / 16, mid = begin + 16 * ((chunks + 1) / 2);
    std::nth_element(items + begin, items + mid, items + end,
                     [axis](const Keyed &a, const Keyed &b) { return a.centroid[axis] < b.centroid[axis]; });
    orderChunks(items, begin, mid);
    orderChunks(items, mid, end);
}
} // namespace

void TriangleStore::setLeaf(size_t offset, const uint32_t *ids, uint32_t n,
                            const std::vector<std::array<Point3f, 3>> &vertices) {
    std::vector<uint32_t> prims(ids, ids + n);
    if (n > 16) {
        std::vector<Keyed> items(n);
        for (uint32_t i = 0; i < n; ++i) {
            const auto &v = vertices[ids[i]];
            items[i] = {v[0] + v[1] + v[2], ids[i]};
        }
        orderChunks(items.data(), 0, n);
        for (uint32_t i = 0; i < n; ++i) prims[i] = items[i].prim;
    }
    float *rows = m_data.data() + offset;
    for (uint32_t i = 0; i < n; ++i) {
        const std::array<Point3f, 3> &p = vertices[prims[i]];
        std::memcpy(rows + size_t(9) * n + i, &prims[i], sizeof(uint32_t));
        for (int c = 0; c < 3; ++c) {
            rows[(0 + c) * n + i] = p[0][c];
            if (m_kind == Intersector::MT) {
                rows[(3 + c) * n + i] = p[1][c] - p[0][c];
                rows[(6 + c) * n + i] = p[2][c] - p[0][c];
            } else {
                rows[(3 + c) * n + i] = p[1][c];
                rows[(6 + c) * n + i] = p[2][c];
            }
        }
    }
    if (n <= 16) return;
    // Chunk boxes, structure of arrays: rows min x, y, z, max x, y, z of nc floats.
    const uint32_t nc = (n + 15) / 16;
    float *boxes = rows + size_t(10) * n;
    for (uint32_t k = 0; k < nc; ++k) {
        BoundingBox3f b;
        for (uint32_t i = 16 * k; i < std::min(n, 16 * k + 16); ++i)
            for (int c = 0; c < 3; ++c) b.expandBy(vertices[prims[i]][c]);
        for (int a = 0; a < 3; ++a) {
            boxes[size_t(a) * nc + k] = b.min[a];
            boxes[size_t(3 + a) * nc + k] = b.max[a];
        }
    }
}

namespace {
/// Load triangle i of a leaf whose rows have stride n.
inline void loadCorner(const float *rows, uint32_t n, uint32_t i, int first, float out[3]) {
    out[0] = rows[(first + 0) * n + i];
    out[1] = rows[(first + 1) * n + i];
    out[2] = rows[(first + 2) * n + i];
}

inline uint32_t primAt(const float *rows, uint32_t n, uint32_t i) {
    uint32_t p;
    std::memcpy(&p, rows + size_t(9) * n + i, sizeof(uint32_t));
    return p;
}

/// Scalar kernel on one triangle of a leaf.
inline bool testOne(Intersector kind, const TriangleRay &ray, const float *rows, uint32_t n, uint32_t i, float maxt,
                    float &t, float &u, float &v) {
    float a[3], b[3], c[3];
    loadCorner(rows, n, i, 0, a);
    loadCorner(rows, n, i, 3, b);
    loadCorner(rows, n, i, 6, c);
    return kind == Intersector::MT ? intersectMT(ray, a, b, c, maxt, t, u, v)
                                   : intersectWatertight(ray, a, b, c, maxt, t, u, v);
}

/// Scalar closest hit over chunk k (triangles 16k .. 16k + 15); lexicographic minimum (t, prim).
bool chunkIntersectScalar(Intersector kind, const TriangleRay &ray, const float *rows, uint32_t n, uint32_t k,
                          Hit &best) {
    bool found = false;
    for (uint32_t i = 16 * k; i < std::min(n, 16 * k + 16); ++i) {
        float t, u, v;
        uint32_t prim = primAt(rows, n, i);
        if (testOne(kind, ray, rows, n, i, best.t, t, u, v) && (t < best.t || prim < best.prim)) {
            best = Hit{t, u, v, prim};
            found = true;
        }
    }
    return found;
}

/// Entry distances of the ray into chunk boxes [16 g, 16 g + 16) of a leaf with nc chunks;
/// bit j of the result is set when chunk 16 g + j is entered within [ray.mint, maxt].
/// The conservative slab test of the octree nodes; NaN never narrows the interval.
unsigned chunkEntriesScalar(const TriangleRay &r, const float *rows, uint32_t n, uint32_t g, float maxt, float tn[16]) {
    const uint32_t nc = (n + 15) / 16;
    const float *boxes = rows + size_t(10) * n;
    unsigned mask = 0;
    for (uint32_t j = 0; j < 16 && 16 * g + j < nc; ++j) {
        uint32_t k = 16 * g + j;
        float t0 = r.mint, t1 = maxt;
        for (int a = 0; a < 3; ++a) {
            float tNear = (boxes[(3 * r.neg[a] + a) * nc + k] - r.o[a]) * r.rcpNear[a];
            float tFar = (boxes[(3 * (1 - r.neg[a]) + a) * nc + k] - r.o[a]) * r.rcpFar[a];
            t0 = tNear > t0 ? tNear : t0;
            t1 = tFar < t1 ? tFar : t1;
        }
        tn[j] = t0;
        if (t0 <= t1) mask |= 1u << j;
    }
    return mask;
}

/// Loop over a leaf: chunks in order of entry distance (ties: lower index), skipping those
/// entered beyond the closest hit; every kernel width visits exactly the same chunks.
/// \p entries and \p chunkHit have the signatures of chunkEntriesScalar / chunkIntersectScalar.
template <typename Entries, typename ChunkHit>
bool intersectChunks(Intersector kind, const TriangleRay &ray, const float *rows, uint32_t n, Hit &best,
                     Entries entries, ChunkHit chunkHit) {
    if (n <= 16) return chunkHit(kind, ray, rows, n, 0, best);
    bool found = false;
    const uint32_t nc = (n + 15) / 16;
    for (uint32_t g = 0; 16 * g < nc; ++g) {
        float tn[16];
        unsigned mask = entries(ray, rows, n, g, best.t, tn);
        while (mask) {
            int k = -1;
            for (unsigned m = mask; m; m &= m - 1) {
                int j = __builtin_ctz(m);
                if (k < 0 || tn[j] < tn[k]) k = j;
            }
            if (tn[k] > best.t) break;
            mask &= ~(1u << k);
            found |= chunkHit(kind, ray, rows, n, 16 * g + uint32_t(k), best);
        }
    }
    return found;
}

bool intersectScalar(Intersector kind, const TriangleRay &ray, const float *rows, uint32_t n, Hit &best) {
    return intersectChunks(kind, ray, rows, n, best, chunkEntriesScalar, chunkIntersectScalar);
}

#if NORI_TRIANGLE_AVX512 || NORI_TRIANGLE_AVX2
// The SIMD kernels, written once for both widths: __m512 (sixteen lanes, AVX-512) and __m256
// (eight lanes, AVX2). Every lane performs exactly the scalar kernels' operations in the same
// order (no FMA in this file), so the answers are bit-identical to the scalar ones. Lane masks
// are bit sets (bit j: lane j), in mask registers with AVX-512.

#if NORI_TRIANGLE_AVX512
using Wide = __m512;
using LaneMask = __mmask16;  // kept in mask registers
inline Wide splat(float x) { return _mm512_set1_ps(x); }
inline Wide add(Wide a, Wide b) { return _mm512_add_ps(a, b); }
inline Wide sub(Wide a, Wide b) { return _mm512_sub_ps(a, b); }
inline Wide mul(Wide a, Wide b) { return _mm512_mul_ps(a, b); }
inline Wide div(Wide a, Wide b) { return _mm512_div_ps(a, b); }
template <int Predicate>
inline LaneMask cmp(Wide a, Wide b) { return _mm512_cmp_ps_mask(a, b, Predicate); }
/// Lanes in \p m read from \p p, the others are zero (and never read from memory).
inline Wide loadLanes(const float *p, LaneMask m) { return _mm512_maskz_loadu_ps(m, p); }
#else
using Wide = __m256;
using LaneMask = unsigned;
inline Wide splat(float x) { return _mm256_set1_ps(x); }
inline Wide add(Wide a, Wide b) { return _mm256_add_ps(a, b); }
inline Wide sub(Wide a, Wide b) { return _mm256_sub_ps(a, b); }
inline Wide mul(Wide a, Wide b) { return _mm256_mul_ps(a, b); }
inline Wide div(Wide a, Wide b) { return _mm256_div_ps(a, b); }
template <int Predicate>
inline LaneMask cmp(Wide a, Wide b) { return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(a, b, Predicate))); }
inline Wide loadLanes(const float *p, LaneMask m) {
    const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_maskload_ps(p, _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(m)), bits), bits));
}
#endif

/// One SIMD step over consecutive triangles of a leaf.
struct Lanes {
    Wide t, u, v;
    LaneMask valid;  ///< lanes with a hit in [mint, maxt]
    LaneMask redo;   ///< watertight lanes that need the double-precision edge functions
};

inline Wide load(const float *rows, uint32_t n, int row, uint32_t i, LaneMask m) {
    return loadLanes(rows + size_t(row) * n + i, m);
}

inline Lanes mtLanes(const TriangleRay &r, const float *rows, uint32_t n, uint32_t i, LaneMask m, float maxt) {
    const Wide dx = splat(r.d[0]), dy = splat(r.d[1]), dz = splat(r.d[2]);
    Wide e1x = load(rows, n, 3, i, m), e1y = load(rows, n, 4, i, m), e1z = load(rows, n, 5, i, m);
    Wide e2x = load(rows, n, 6, i, m), e2y = load(rows, n, 7, i, m), e2z = load(rows, n, 8, i, m);
    Wide px = sub(mul(dy, e2z), mul(dz, e2y));
    Wide py = sub(mul(dz, e2x), mul(dx, e2z));
    Wide pz = sub(mul(dx, e2y), mul(dy, e2x));
    Wide det = add(add(mul(e1x, px), mul(e1y, py)), mul(e1z, pz));
    const Wide zero = splat(0.0f), one = splat(1.0f);
    LaneMask valid = m & cmp<_CMP_NEQ_UQ>(det, zero);
    Wide invDet = div(one, det);
    Wide tx = sub(splat(r.o[0]), load(rows, n, 0, i, m));
    Wide ty = sub(splat(r.o[1]), load(rows, n, 1, i, m));
    Wide tz = sub(splat(r.o[2]), load(rows, n, 2, i, m));
    Wide u = mul(add(add(mul(tx, px), mul(ty, py)), mul(tz, pz)), invDet);
    // Scalar: reject if (u < 0 || u > 1); ordered compares keep NaN lanes, as the scalar code does.
    valid &= ~(cmp<_CMP_LT_OQ>(u, zero) | cmp<_CMP_GT_OQ>(u, one));
    Wide qx = sub(mul(ty, e1z), mul(tz, e1y));
    Wide qy = sub(mul(tz, e1x), mul(tx, e1z));
    Wide qz = sub(mul(tx, e1y), mul(ty, e1x));
    Wide v = mul(add(add(mul(dx, qx), mul(dy, qy)), mul(dz, qz)), invDet);
    valid &= ~(cmp<_CMP_LT_OQ>(v, zero) | cmp<_CMP_GT_OQ>(add(u, v), one));
    Wide t = mul(add(add(mul(e2x, qx), mul(e2y, qy)), mul(e2z, qz)), invDet);
    valid &= cmp<_CMP_GE_OQ>(t, splat(r.mint)) & cmp<_CMP_LE_OQ>(t, splat(maxt));
    return {t, u, v, valid, 0};
}

inline Lanes watertightLanes(const TriangleRay &r, const float *rows, uint32_t n, uint32_t i, LaneMask m, float maxt) {
    const Wide ox = splat(r.o[r.kx]), oy = splat(r.o[r.ky]), oz = splat(r.o[r.kz]);
    const Wide sx = splat(r.sx), sy = splat(r.sy), sz = splat(r.sz);
    Wide az0 = sub(load(rows, n, r.kz, i, m), oz);
    Wide bz0 = sub(load(rows, n, 3 + r.kz, i, m), oz);
    Wide cz0 = sub(load(rows, n, 6 + r.kz, i, m), oz);
    Wide ax = sub(sub(load(rows, n, r.kx, i, m), ox), mul(sx, az0));
    Wide ay = sub(sub(load(rows, n, r.ky, i, m), oy), mul(sy, az0));
    Wide bx = sub(sub(load(rows, n, 3 + r.kx, i, m), ox), mul(sx, bz0));
    Wide by = sub(sub(load(rows, n, 3 + r.ky, i, m), oy), mul(sy, bz0));
    Wide cx = sub(sub(load(rows, n, 6 + r.kx, i, m), ox), mul(sx, cz0));
    Wide cy = sub(sub(load(rows, n, 6 + r.ky, i, m), oy), mul(sy, cz0));
    Wide U = sub(mul(cx, by), mul(cy, bx));
    Wide V = sub(mul(ax, cy), mul(ay, cx));
    Wide W = sub(mul(bx, ay), mul(by, ax));
    const Wide zero = splat(0.0f);
    LaneMask redo = m & (cmp<_CMP_EQ_OQ>(U, zero) | cmp<_CMP_EQ_OQ>(V, zero) | cmp<_CMP_EQ_OQ>(W, zero));
    LaneMask neg = cmp<_CMP_LT_OQ>(U, zero) | cmp<_CMP_LT_OQ>(V, zero) | cmp<_CMP_LT_OQ>(W, zero);
    LaneMask pos = cmp<_CMP_GT_OQ>(U, zero) | cmp<_CMP_GT_OQ>(V, zero) | cmp<_CMP_GT_OQ>(W, zero);
    LaneMask valid = m & ~redo & ~(neg & pos);
    if (!valid) return {U, V, W, 0, redo};  // most steps: the ray passes beside every triangle
    Wide det = add(add(U, V), W);
    valid &= cmp<_CMP_NEQ_UQ>(det, zero);
    Wide T = add(add(mul(U, mul(sz, az0)), mul(V, mul(sz, bz0))), mul(W, mul(sz, cz0)));
    Wide invDet = div(splat(1.0f), det);
    Wide t = mul(T, invDet);
    valid &= cmp<_CMP_GE_OQ>(t, splat(r.mint)) & cmp<_CMP_LE_OQ>(t, splat(maxt));
    return {t, mul(V, invDet), mul(W, invDet), valid, redo};
}

inline Lanes testLanes(Intersector kind, const TriangleRay &r, const float *rows, uint32_t n, uint32_t i, unsigned m,
                       float maxt) {
    return kind == Intersector::MT ? mtLanes(r, rows, n, i, m, maxt) : watertightLanes(r, rows, n, i, m, maxt);
}
#endif

#if NORI_TRIANGLE_AVX2
/// Lanes of the 8-triangle step starting at triangle i (the tail step is partial).
inline unsigned stepMask8(uint32_t n, uint32_t i) { return n - i >= 8 ? 0xFFu : (1u << (n - i)) - 1; }

/// Closest hit over chunk k in two 8-lane steps; lexicographic minimum (t, prim) as the scalar loop.
bool chunkIntersectAvx2(Intersector kind, const TriangleRay &ray, const float *rows, uint32_t n, uint32_t k,
                        Hit &best) {
    bool found = false;
    for (uint32_t i = 16 * k; i < std::min(n, 16 * k + 16); i += 8) {
        Lanes l = testLanes(kind, ray, rows, n, i, stepMask8(n, i), best.t);
        unsigned candidates = l.valid | l.redo;
        if (!candidates) continue;
        alignas(32) float ts[8], us[8], vs[8];
        _mm256_store_ps(ts, l.t);
        _mm256_store_ps(us, l.u);
        _mm256_store_ps(vs, l.v);
        for (; candidates; candidates &= candidates - 1) {
            int j = __builtin_ctz(candidates);
            uint32_t prim = primAt(rows, n, i + uint32_t(j));
            float t = ts[j], u = us[j], v = vs[j];
            // Lanes with an exactly zero edge function: the scalar kernel decides them.
            if ((l.redo >> j) & 1u) {
                if (!testOne(kind, ray, rows, n, i + uint32_t(j), best.t, t, u, v)) continue;
            }
            if (t < best.t || (t == best.t && prim < best.prim)) {
                best = Hit{t, u, v, prim};
                found = true;
            }
        }
    }
    return found;
}

/// The same values as chunkEntriesScalar(), eight chunk boxes per step.
unsigned chunkEntriesAvx2(const TriangleRay &r, const float *rows, uint32_t n, uint32_t g, float maxt, float tn[16]) {
    const uint32_t nc = (n + 15) / 16;
    const float *boxes = rows + size_t(10) * n;
    unsigned mask = 0;
    for (uint32_t k = 16 * g; k < std::min(nc, 16 * g + 16); k += 8) {
        const unsigned m = stepMask8(nc, k);
        __m256 t0 = _mm256_set1_ps(r.mint), t1 = _mm256_set1_ps(maxt);
        for (int a = 0; a < 3; ++a) {
            __m256 o = _mm256_set1_ps(r.o[a]);
            __m256 nearPlane = loadLanes(boxes + size_t(3 * r.neg[a] + a) * nc + k, m);
            __m256 farPlane = loadLanes(boxes + size_t(3 * (1 - r.neg[a]) + a) * nc + k, m);
            __m256 tNear = mul(sub(nearPlane, o), _mm256_set1_ps(r.rcpNear[a]));
            __m256 tFar = mul(sub(farPlane, o), _mm256_set1_ps(r.rcpFar[a]));
            t0 = _mm256_max_ps(tNear, t0);  // second operand on NaN or equality: as the scalar code
            t1 = _mm256_min_ps(tFar, t1);
        }
        _mm256_storeu_ps(tn + (k - 16 * g), t0);
        mask |= (m & cmp<_CMP_LE_OQ>(t0, t1)) << (k - 16 * g);
    }
    return mask;
}

/// Any hit in chunk k with t in [mint, maxt].
bool chunkOccludedAvx2(Intersector kind, const TriangleRay &ray, const float *rows, uint32_t n, uint32_t k,
                       float maxt) {
    for (uint32_t i = 16 * k; i < std::min(n, 16 * k + 16); i += 8) {
        Lanes l = testLanes(kind, ray, rows, n, i, stepMask8(n, i), maxt);
        if (l.valid) return true;
        for (unsigned redo = l.redo; redo; redo &= redo - 1) {
            float t, u, v;
            if (testOne(kind, ray, rows, n, i + uint32_t(__builtin_ctz(redo)), maxt, t, u, v)) return true;
        }
    }
    return false;
}
#endif

} // namespace

#if NORI_TRIANGLE_AVX512
namespace {
/// Minimum over the lanes in \p mask (GCC 12's masked reduction trips -Wuninitialized).
inline float reduceMin(__mmask16 mask, __m512 v) {
    return _mm512_reduce_min_ps(_mm512_mask_blend_ps(mask, _mm512_set1_ps(Infinity), v));
}

/// SIMD closest hit over chunk k: one 16-lane step.
bool chunkIntersectSimd(Intersector kind, const TriangleRay &ray, const float *rows, uint32_t n, uint32_t k, Hit &best) {
    const uint32_t i = 16 * k;
    const float *prims = rows + size_t(9) * n;
    __mmask16 m = n - i >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << (n - i)) - 1);
    Lanes l = testLanes(kind, ray, rows, n, i, m, best.t);
    bool found = false;
    // Rare watertight lanes with an exactly zero edge function: the scalar kernel
    // (double-precision fallback) decides them one by one.
    for (unsigned redo = l.redo; redo; redo &= redo - 1) {
        uint32_t j = i + uint32_t(__builtin_ctz(redo));
        float t, u, v;
        uint32_t prim = primAt(rows, n, j);
        if (testOne(kind, ray, rows, n, j, best.t, t, u, v) && (t < best.t || prim < best.prim)) {
            best = Hit{t, u, v, prim};
            found = true;
        }
    }
    if (!l.valid) return found;
    // Lexicographic minimum of (t, prim) over the hit lanes, as the scalar loop finds it.
    float tmin = reduceMin(l.valid, l.t);
    __mmask16 nearest = _mm512_mask_cmp_ps_mask(l.valid, l.t, _mm512_set1_ps(tmin), _CMP_EQ_OQ);
    __m512i ids = _mm512_maskz_loadu_epi32(m, prims + i);
    uint32_t prim = uint32_t(_mm512_reduce_min_epu32(_mm512_mask_blend_epi32(nearest, _mm512_set1_epi32(-1), ids)));
    if (!(tmin < best.t || (tmin == best.t && prim < best.prim))) return found;
    __mmask16 lane = _mm512_mask_cmp_epu32_mask(nearest, ids, _mm512_set1_epi32(int(prim)), _MM_CMPINT_EQ);
    int j = __builtin_ctz(lane);
    alignas(64) float us[16], vs[16];
    _mm512_store_ps(us, l.u);
    _mm512_store_ps(vs, l.v);
    best = Hit{tmin, us[j], vs[j], prim};
    return true;
}

/// The same values as chunkEntriesScalar(), sixteen chunk boxes at once.
__mmask16 chunkEntriesSimd(const TriangleRay &r, const float *rows, uint32_t n, uint32_t g, float maxt, __m512 &tn) {
    const uint32_t nc = (n + 15) / 16;
    const float *boxes = rows + size_t(10) * n + 16 * g;
    __mmask16 m = nc - 16 * g >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << (nc - 16 * g)) - 1);
    __m512 t0 = _mm512_set1_ps(r.mint), t1 = _mm512_set1_ps(maxt);
    for (int a = 0; a < 3; ++a) {
        __m512 o = _mm512_set1_ps(r.o[a]);
        __m512 nearPlane = _mm512_maskz_loadu_ps(m, boxes + size_t(3 * r.neg[a] + a) * nc);
        __m512 farPlane = _mm512_maskz_loadu_ps(m, boxes + size_t(3 * (1 - r.neg[a]) + a) * nc);
        __m512 tNear = _mm512_mul_ps(_mm512_sub_ps(nearPlane, o), _mm512_set1_ps(r.rcpNear[a]));
        __m512 tFar = _mm512_mul_ps(_mm512_sub_ps(farPlane, o), _mm512_set1_ps(r.rcpFar[a]));
        t0 = _mm512_max_ps(tNear, t0);  // second operand on NaN or equality: as the scalar code
        t1 = _mm512_min_ps(tFar, t1);
    }
    tn = t0;
    return _mm512_mask_cmp_ps_mask(m, t0, t1, _CMP_LE_OQ);
}
} // namespace
#endif

bool TriangleStore::intersect(const TriangleRay &ray, size_t offset, uint32_t n, Hit &best) const {
    const float *rows = m_data.data() + offset;
#if NORI_TRIANGLE_AVX512
    if (n <= 16) return chunkIntersectSimd(m_kind, ray, rows, n, 0, best);
    bool found = false;
    const uint32_t nc = (n + 15) / 16;
    for (uint32_t g = 0; 16 * g < nc; ++g) {
        __m512 tn;
        __mmask16 mask = chunkEntriesSimd(ray, rows, n, g, best.t, tn);
        while (mask) {  // nearest entered chunk first (ties: lower index)
            float tmin = reduceMin(mask, tn);
            if (tmin > best.t) break;
            __mmask16 at = _mm512_mask_cmp_ps_mask(mask, tn, _mm512_set1_ps(tmin), _CMP_EQ_OQ);
            int k = __builtin_ctz(at);
            mask &= __mmask16(~(1u << k));
            found |= chunkIntersectSimd(m_kind, ray, rows, n, 16 * g + uint32_t(k), best);
        }
    }
    return found;
#elif NORI_TRIANGLE_AVX2
    return intersectChunks(m_kind, ray, rows, n, best, chunkEntriesAvx2, chunkIntersectAvx2);
#else
    return intersectScalar(m_kind, ray, rows, n, best);
#endif
}

bool TriangleStore::occluded(const TriangleRay &ray, size_t offset, uint32_t n, float maxt) const {
    const float *rows = m_data.data() + offset;
    const uint32_t nc = (n + 15) / 16;
    for (uint32_t g = 0; 16 * g < nc; ++g) {
#if NORI_TRIANGLE_AVX512
        __m512 tn;
        unsigned mask = n <= 16 ? 1u : chunkEntriesSimd(ray, rows, n, g, maxt, tn);
#elif NORI_TRIANGLE_AVX2
        float tn[16];
        unsigned mask = n <= 16 ? 1u : chunkEntriesAvx2(ray, rows, n, g, maxt, tn);
#else
        float tn[16];
        unsigned mask = n <= 16 ? 1u : chunkEntriesScalar(ray, rows, n, g, maxt, tn);
#endif
        for (; mask; mask &= mask - 1) {
            uint32_t k = 16 * g + uint32_t(__builtin_ctz(mask));
#if NORI_TRIANGLE_AVX512
            __mmask16 m = n - 16 * k >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << (n - 16 * k)) - 1);
            Lanes l = testLanes(m_kind, ray, rows, n, 16 * k, m, maxt);
            if (l.valid) return true;
            for (unsigned redo = l.redo; redo; redo &= redo - 1) {
                float t, u, v;
                if (testOne(m_kind, ray, rows, n, 16 * k + uint32_t(__builtin_ctz(redo)), maxt, t, u, v)) return true;
            }
#elif NORI_TRIANGLE_AVX2
            if (chunkOccludedAvx2(m_kind, ray, rows, n, k, maxt)) return true;
#else
            for (uint32_t i = 16 * k; i < std::min(n, 16 * k + 16); ++i) {
                float t, u, v;
                if (testOne(m_kind, ray, rows, n, i, maxt, t, u, v)) return true;
            }
#endif
        }
    }
    return false;
}

bool TriangleStore::intersectReference(const TriangleRay &ray, size_t offset, uint32_t n, Hit &best) const {
    return intersectScalar(m_kind, ray, m_data.data() + offset, n, best);
}

} // namespace nori
