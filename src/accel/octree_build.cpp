/// \file octree_build.cpp
/// \brief The octree's recursive midpoint subdivision: which axes a cell splits, which child
/// cells each triangle touches, which triangles stay in the node, and when a cell is a leaf.
#include "octree_build.h"
#include "stack_arena.h"
#include "triangle_box.h"
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

namespace nori::octree_build {

namespace {

using Rule = OctreeAccel::BuildRule;

/// Subtrees with more references than this are built as parallel tasks.
constexpr size_t kParallelRefs = 4096;

/// The classification's block of references (see split()).
constexpr size_t kBlock = 64;

/// The whole tree holds at most this many references per triangle (see split()): `count` and
/// `seed` (which copy a triangle into every cell it touches) and `sah` (which sends triangles
/// down loose once its budget is spent; 1.5 keeps the bytes per triangle below Embree's).
constexpr double kRefBudget = 8.0;
constexpr double kSahRefBudget = 1.5;

/// Surface-area cost model (Goldsmith & Salmon 1987; MacDonald & Booth 1990): a ray that
/// enters a box of area A enters a box of area a inside it with probability a / A. The unit is
/// one inner-node visit (one eight-box slab test and its stack pushes). A sampling profile of
/// the AVX-512 build (perf, cpu-clock, generated city, primary rays: 36 % of the time in the
/// node loop for 5.9 nodes per ray, 32 % in the chunk kernel for 3.4 chunks per ray) puts one
/// sixteen-lane triangle chunk at about 1.6 node visits. kChunk 2 against the earlier 3, all
/// 20 bench rows (thread CPU time, octree over Embree, 4 spp): rays 0-12 % faster on 17 rows
/// (wide 0.94 -> 1.03 primary, tabletop 0.83 -> 0.93 shadow, stadium 0.68 -> 0.75 diffuse,
/// full dragon 0.71 -> 0.77 diffuse), 2-3 % slower on city and pa5 table (within the noise),
/// 1-6 % fewer bytes everywhere; 1.5 helps the meshes more but drops city below 0.7 primary.
///
/// A leaf of more than 16 triangles is not tested whole: its chunks are spatially compact
/// (TriangleStore::setLeaf orders them by median splits) and each has a box (one per block of 8
/// since the tenth round, so a ray often pays half a chunk: TriangleStore::blockSize; the prices
/// below were measured with boxes per 16, and 1.5 or 2.5 for kChunk measured no better since,
/// nor did pricing 8-lane steps at half a chunk: bench/README.md, eleventh round),
/// tested sixteen at a time, so a ray that enters the leaf meets one chunk and a small share of
/// the others (on a surface, the chunk boxes' areas add up to about the surface's, not c times
/// the leaf's).
/// kOtherChunks is that share. Counting every chunk (1.0) made the `sah` tree twice as deep as
/// it pays on meshes, with 6 triangles per leaf; 0.1 (nori-bench, dragon_res2, bunny, sphere,
/// city, grass, stadium, one interleaved run each) halves the nodes, builds 10-30 % faster and
/// keeps the ray ratios within the machine's noise (grass ends with 73 inner nodes).
/// A split's children are further discounted by the rays that stop in a nearer child
/// (split(): termination), which the leaf's price already holds through kOtherChunks.
struct Cost {
    static constexpr double kNode = 1.0;          ///< visiting an inner node
    static constexpr double kChunk = 2.0;         ///< sixteen ray/triangle tests
    static constexpr double kChunkBoxes = 1.0;    ///< sixteen chunk boxes of a leaf above 16 triangles
    static constexpr double kOtherChunks = 0.1;   ///< share of a leaf's other chunks a ray enters

    /// Inner levels a subtree over n references will have above its leaves: log8 of its
    /// chunks, at least one.
    static double levels(size_t n) { return std::max(1.0, std::log(double(n) / 16.0) / std::log(8.0)); }

    /// Testing a list of n triangles (a leaf or a kept list) once the ray reaches it.
    static double list(size_t n) {
        if (n == 0) return 0.0;
        size_t chunks = (n + 15) / 16;
        return chunks == 1 ? kChunk
                           : kChunkBoxes * double((chunks + 15) / 16) +
                                 kChunk * (1.0 + kOtherChunks * double(chunks - 1));
    }
};

/// A kept group's box test (a scalar slab test), paid by every ray that reaches its node, in
/// the cost model's units (Cost: one inner-node visit tests eight boxes at once). Charged for
/// each group beyond a node's first: the model was tuned with one kept list whose box test
/// it did not price, and single lists are decided as before (a charge for every list changed
/// the trees of scenes without a second group, e.g. the cells over a tabletop's objects).
constexpr double kKeptBoxCost = 0.1;

/// A node's kept triangles go into separate groups only where the groups' estimated cost is
/// below this share of one group's. The estimate takes rays as isotropic; rays that come
/// from one side (a camera's) meet boxes that lie one behind another together, each with a
/// chunk test: pa5 veach_mi's plates, four groups priced 11-13 % below one, had primary rays
/// test 1.75 kept chunks instead of 1.29. (Splits that pay: pa5 table's ground and light
/// quad 19 % below one group, most of the generated coplanar scene's 20-50 %.)
constexpr double kGroupMargin = 0.85;

/// The surface area of a box of extents \p ex, \p ey, \p ez; 0 for an empty box (\p valid false).
inline __attribute__((always_inline)) double areaOf(bool valid, float ex, float ey, float ez) {
    if (!valid) return 0.0;
    return 2.0 * (double(ex) * ey + double(ey) * ez + double(ez) * ex);
}

inline double area(const BoundingBox3f &b) {
    const bool valid = b.max.x() >= b.min.x() && b.max.y() >= b.min.y() && b.max.z() >= b.min.z();  // isValid()
    const Vector3f e = b.extents();
    return areaOf(valid, e.x(), e.y(), e.z());
}

/// The `sah` rule splits a cell by three successive midpoint bisections, each of the longest
/// side of the part being split, so cells stay near-cubic (no side more than twice another,
/// beyond what the scene's own flatness imposes): a cube gets the octree's eight octants, a
/// 1000 x 3 x 25 strip eight slabs along its length, and no cell ever becomes a thin slab that
/// every triangle crosses. Each node still has eight children, so the eight-box test stays
/// fully used. The other rules split x, y and z once each: the classic octree.
OctreeNode::Pattern patternFor(Rule rule, const BoundingBox3f &cell) {
    OctreeNode::Pattern p{{0, 1, 2}};
    if (rule != Rule::Sah) return p;
    Vector3f e = cell.extents();
    for (int level = 0; level < 3; ++level) {
        int a = e.x() >= e.y() && e.x() >= e.z() ? 0 : (e.y() >= e.z() ? 1 : 2);
        p.axis[level] = uint8_t(a);
        e[a] *= 0.5f;
    }
    return p;
}

/// Cell of child slot \p c of \p cell: bit 2 - l of c selects the upper half of bisection l.
BoundingBox3f cellOf(const BoundingBox3f &cell, const OctreeNode::Pattern &p, int c) {
    BoundingBox3f b = cell;
    for (int level = 0; level < 3; ++level) {
        int a = p.axis[level];
        float mid = 0.5f * (b.min[a] + b.max[a]);
        if ((c >> (2 - level)) & 1) b.min[a] = mid;
        else b.max[a] = mid;
    }
    return b;
}

/// Four floats in one vector register (a GCC/clang vector extension; SSE on x86-64), for the
/// classification and the gathering pass. Points as (x, y, z, unused).
typedef float Float4 __attribute__((vector_size(16)));
typedef int32_t Int4 __attribute__((vector_size(16)));
inline Float4 load4(const float *p) {
    Float4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline Float4 load4(const Point3f &p) { return Float4{p.x(), p.y(), p.z(), 0.0f}; }
// The same comparisons as the scalar code they replace, operand for operand, so that even the
// sign of a zero bound comes out the same.
inline Float4 max4(Float4 a, Float4 b) { return a > b ? a : b; }
inline Float4 min4(Float4 a, Float4 b) { return a < b ? a : b; }

/// A box as two four-lane vectors (the fourth lanes unused, any bits): the kept-group
/// search's boxes, which it joins and measures for every candidate and group (with
/// BoundingBox3f's scalar operations that loop was half of the search). Each operation takes
/// the operands as BoundingBox3f's does (Eigen's cwiseMin and cwiseMax, like std::min and
/// std::max, keep the first operand where the two compare equal), so even a zero bound keeps
/// its sign and the groups come out bit for bit as BoundingBox3f made them.
struct VecBox {
    Float4 lo = Float4{} + Infinity, hi = Float4{} - Infinity;

    /// \p r's bounds clipped to the box \p lo, \p hi (cwiseMax(lo), cwiseMin(hi)).
    static VecBox clipped(const float *rlo, const float *rhi, Float4 boxLo, Float4 boxHi) {
        const Float4 a = load4(rlo), b = load4(rhi);
        return {a < boxLo ? boxLo : a, boxHi < b ? boxHi : b};
    }
    void expandBy(const VecBox &b) {
        lo = b.lo < lo ? b.lo : lo;
        hi = hi < b.hi ? b.hi : hi;
    }
    double area() const {
        const Float4 e = hi - lo;
        return areaOf(hi[0] >= lo[0] && hi[1] >= lo[1] && hi[2] >= lo[2], e[0], e[1], e[2]);
    }
    BoundingBox3f box() const { return BoundingBox3f(Point3f(lo[0], lo[1], lo[2]), Point3f(hi[0], hi[1], hi[2])); }
};

/// Classifier::mask111's table for the classic layout under \p pattern (one bisection per
/// axis, in any order) and the plane rule \p oneSide: bits 0-2 of an index give the first slab
/// per axis, bits 3-5 the last; the entry is the mask of the cells in those slabs. It depends
/// only on which bit of a slot each axis sets, not on the cell, so it is made once per order
/// (filling it for every node was 5 % of the build's instructions).
const uint8_t *tableFor111(const OctreeNode::Pattern &pattern, bool oneSide) {
    static const auto tables = [] {
        std::array<std::array<uint8_t, 64>, 128> t{};
        for (uint32_t code = 0; code < 64; ++code) {
            const OctreeNode::Pattern p = OctreeNode::Pattern::fromCode(code);
            int level[3] = {-1, -1, -1};  // the level that bisects each axis
            for (int l = 0; l < 3; ++l)
                if (p.axis[l] < 3) level[p.axis[l]] = l;
            if (level[0] < 0 || level[1] < 0 || level[2] < 0) continue;
            for (int side = 0; side < 2; ++side)
                for (unsigned bits = 0; bits < 64; ++bits) {
                    unsigned m = 0xFFu;
                    for (int a = 0; a < 3; ++a) {
                        unsigned first = (bits >> a) & 1u, last = (bits >> (3 + a)) & 1u;
                        if (side) last = last > first ? last : first;
                        // The cells whose slab along a (their bit at level[a]) is in [first, last].
                        unsigned cells = 0;
                        for (int c = 0; c < 8; ++c) {
                            unsigned slab = (unsigned(c) >> (2 - level[a])) & 1u;
                            if (slab >= first && slab <= last) cells |= 1u << c;
                        }
                        m &= cells;
                    }
                    t[2 * code + side][bits] = uint8_t(m);
                }
        }
        return t;
    }();
    return tables[2 * pattern.code() + (oneSide ? 1 : 0)].data();
}

/// The child cells a bounding box touches (closed: touching a plane counts), by a table per
/// axis: along each axis the eight cells form up to eight slabs, a box covers a run of them,
/// and range[a][first][last] is the mask of the cells in that run.
struct Classifier {
    int planes[3] = {};      ///< interior slab boundaries per axis
    float plane[3][7] = {};  ///< their positions, increasing
    Float4 planes4[3][2];    ///< the same, four to a vector, padded with +inf
    uint8_t range[3][8][8] = {};
    uint8_t axis[3] = {};    ///< the pattern's bisection axes, level by level
    float mid[7] = {};       ///< bisection planes: level l, cells above prefix q at mid[2^l - 1 + q]
    /// The classic layout (one bisection per axis, every rule's cubic cells): the three planes
    /// in one vector, and the mask for each outcome of the six comparisons (bits 0-2: first
    /// slab per axis, bits 3-5: last slab per axis).
    Float4 planes111 = {};
    const uint8_t *table111 = nullptr;

    /// Closed cells (false: a box touching a plane goes to both sides, as the `count` and
    /// `seed` rules do) or one side (true, `sah`): a box that only touches a plane from one
    /// side, or lies in it, goes to one cell. That cell's closed extent holds the whole
    /// triangle, and the traversal visits every child box a ray enters before its closest hit,
    /// so the ray meets the triangle there; copying it into the other cell only doubles the
    /// work. Faces on split planes (walls of stacked boxes, grid-aligned geometry) would
    /// otherwise all be copied, or kept high in the tree as "large".
    bool oneSide = false;

    /// \p cells: the children of \p cell by \p pattern. Along axis a the slabs are the
    /// bisections on a: none (one slab), one (two), or nested ones (up to eight).
    Classifier(const BoundingBox3f &cell, const OctreeNode::Pattern &pattern, const BoundingBox3f cells[8], bool oneSideIn)
        : oneSide(oneSideIn) {
        for (int a = 0; a < 3; ++a) {
            // Slab of each cell along a: its bits at the levels that bisect a.
            int bisections = 0, slabOf[8] = {};
            for (int level = 0; level < 3; ++level)
                if (pattern.axis[level] == a) {
                    ++bisections;
                    for (int c = 0; c < 8; ++c) slabOf[c] = 2 * slabOf[c] + ((c >> (2 - level)) & 1);
                }
            const int slabs = 1 << bisections;
            uint8_t slabMask[8] = {};
            for (int c = 0; c < 8; ++c) {
                slabMask[slabOf[c]] |= uint8_t(1u << c);
                if (slabOf[c] > 0) plane[a][slabOf[c] - 1] = cells[c].min[a];
            }
            planes[a] = slabs - 1;
            for (int first = 0; first < slabs; ++first) {
                uint8_t m = 0;
                for (int last = first; last < slabs; ++last) range[a][first][last] = m |= slabMask[last];
            }
        }
        (void)cell;
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k < 8; ++k) planes4[a][k / 4][k % 4] = k < planes[a] && k < 7 ? plane[a][k] : Infinity;
        if (planes[0] == 1 && planes[1] == 1 && planes[2] == 1) {
            planes111 = Float4{plane[0][0], plane[1][0], plane[2][0], Infinity};
            table111 = tableFor111(pattern, oneSide);
        }
        // The plane of bisection l under prefix q is the lower side of the first cell above it
        // (cellOf's arithmetic: the same float).
        for (int level = 0; level < 3; ++level) {
            axis[level] = pattern.axis[level];
            for (int q = 0; q < (1 << level); ++q)
                mid[(1 << level) - 1 + q] = cells[((2 * q + 1) << (2 - level))].min[pattern.axis[level]];
        }
    }
    /// Slot whose cell holds the centre of [lo, hi] (the upper cell on a plane).
    int slotOfCentre(const float lo[3], const float hi[3]) const {
        int c = 0;
        for (int level = 0; level < 3; ++level) {
            const int a = axis[level];
            c = 2 * c + int(0.5f * (lo[a] + hi[a]) >= mid[(1 << level) - 1 + c]);
        }
        return c;
    }
    /// (`oneSide`) The one cell that every bounding box inside [lo, hi] goes to, or 0 when
    /// they may go to different cells. Along each axis a box [l, h] inside [lo, hi] starts in
    /// slab (planes <= l) >= (planes <= lo) and ends in slab max(planes <= l, planes < h) <=
    /// (planes <= hi); with no plane in (lo, hi] both bounds are one slab.
    unsigned soleCell(const float lo[3], const float hi[3]) const {
        unsigned m = 0xFFu;
        for (int a = 0; a < 3; ++a) {
            int first = 0, last = 0;
            for (int k = 0; k < planes[a]; ++k) {
                first += plane[a][k] <= lo[a];
                last += plane[a][k] <= hi[a];
            }
            if (first != last) return 0;
            m &= range[a][first][first];
        }
        return (m & (m - 1)) ? 0u : m;
    }
    /// The closed child cells that hold the point \p p (both sides of a plane it lies on; none
    /// outside the cell \p lo, \p hi): along each axis the slabs from the planes below \p p to
    /// those at or below it, BoundingBox3f::contains() of every cell at once.
    unsigned cellsHolding(const Point3f &p, const Point3f &lo, const Point3f &hi) const {
        if (!(p.x() >= lo.x() && p.y() >= lo.y() && p.z() >= lo.z() && p.x() <= hi.x() && p.y() <= hi.y() &&
              p.z() <= hi.z()))
            return 0;
        unsigned m = 0xFFu;
        for (int a = 0; a < 3; ++a) {
#ifdef __SSE__
            // The planes four at a time (padded with +inf, never below a finite point), as
            // axisMask() counts them: the same comparisons without a loop over the planes.
            const Float4 v = Float4{} + p[a];
            unsigned first = unsigned(__builtin_popcount(unsigned(__builtin_ia32_movmskps(Float4(planes4[a][0] < v)))));
            unsigned last = unsigned(__builtin_popcount(unsigned(__builtin_ia32_movmskps(Float4(planes4[a][0] <= v)))));
            if (planes[a] > 3) {
                first += unsigned(__builtin_popcount(unsigned(__builtin_ia32_movmskps(Float4(planes4[a][1] < v)))));
                last += unsigned(__builtin_popcount(unsigned(__builtin_ia32_movmskps(Float4(planes4[a][1] <= v)))));
            }
#else
            int first = 0, last = 0;
            for (int k = 0; k < planes[a]; ++k) {
                first += plane[a][k] < p[a];
                last += plane[a][k] <= p[a];
            }
#endif
            m &= range[a][first][last];
        }
        return m;
    }
    /// Slot whose cell holds the point \p p (slotOfCentre() of a box's centre).
    int slotOfPoint(const float p[3]) const {
        int c = 0;
        for (int level = 0; level < 3; ++level) c = 2 * c + int(p[axis[level]] >= mid[(1 << level) - 1 + c]);
        return c;
    }
    /// Cells along axis \p a that the extent [lo, hi] reaches, for an axis of \p P planes
    /// (P = 0, 1, 3 or 7: no, one, two or three bisections along it).
    template <int P, bool OneSide> unsigned axisMask(int a, float lo, float hi) const {
        if constexpr (P == 0) {
            return 0xFFu;
#ifdef __SSE__
        } else if constexpr (P == 3 || P == 7) {
            // The planes four at a time (padded with +inf, never below a finite bound): a
            // comparison per four planes and the count of its true lanes.
            const Float4 l = Float4{} + lo, h = Float4{} + hi;
            unsigned first = 0, last = 0;
            for (int q = 0; q < (P + 1) / 4; ++q) {
                const Float4 pl = planes4[a][q];
                Int4 f, t;
                if constexpr (OneSide) {
                    f = pl <= l;
                    t = pl < h;
                } else {
                    f = pl < l;
                    t = pl <= h;
                }
                first += unsigned(__builtin_popcount(unsigned(__builtin_ia32_movmskps(Float4(f)))));
                last += unsigned(__builtin_popcount(unsigned(__builtin_ia32_movmskps(Float4(t)))));
            }
            if constexpr (OneSide) last = last > first ? last : first;
            return range[a][first][last];
#endif
        } else {
            unsigned first = 0, last = 0;
            for (int k = 0; k < P; ++k) {
                if constexpr (OneSide) {
                    // Slabs whose open interior the box reaches; a box in a plane takes the upper slab.
                    first += plane[a][k] <= lo;
                    last += plane[a][k] < hi;
                } else {
                    first += plane[a][k] < lo;
                    last += plane[a][k] <= hi;
                }
            }
            if constexpr (OneSide) last = last > first ? last : first;
            return range[a][first][last];
        }
    }
    /// mask() for a known number of planes per axis (see withMask()): the loops unrolled, no
    /// branch per box.
    template <int PX, int PY, int PZ, bool OneSide> unsigned maskOf(const float lo[3], const float hi[3]) const {
        return axisMask<PX, OneSide>(0, lo[0], hi[0]) & axisMask<PY, OneSide>(1, lo[1], hi[1]) &
               axisMask<PZ, OneSide>(2, lo[2], hi[2]);
    }
    /// maskOf<1, 1, 1, OneSide> by two vector comparisons and a table.
    template <bool OneSide> unsigned mask111(const float lo[3], const float hi[3]) const {
        // (x, y, z, hi.x) and (x, y, z, id): the fourth plane is +inf, its comparisons false.
        const Float4 l = load4(lo), h = load4(hi);
        Int4 first, last;
        if constexpr (OneSide) {
            first = planes111 <= l;
            last = planes111 < h;
        } else {
            first = planes111 < l;
            last = planes111 <= h;
        }
#ifdef __SSE__
        // The comparisons' sign bits in one instruction each (movmskps).
        const unsigned f = unsigned(__builtin_ia32_movmskps(Float4(first))) & 7u;
        const unsigned t = unsigned(__builtin_ia32_movmskps(Float4(last))) & 7u;
        return table111[f | t << 3];
#else
        const Int4 bits = (first & Int4{1, 2, 4, 0}) | (last & Int4{8, 16, 32, 0});
        return table111[bits[0] | bits[1] | bits[2]];
#endif
    }
    /// The same for any layout of planes.
    unsigned mask(const float lo[3], const float hi[3]) const {
        unsigned m = 0xFFu;
        for (int a = 0; a < 3; ++a) {
            int first = 0, last = 0;
            for (int k = 0; k < planes[a]; ++k) {
                first += oneSide ? plane[a][k] <= lo[a] : plane[a][k] < lo[a];
                last += oneSide ? plane[a][k] < hi[a] : plane[a][k] <= hi[a];
            }
            if (oneSide) last = last > first ? last : first;
            m &= range[a][first][last];
        }
        return m;
    }
};

/// The `sah` rule's bisections for a node. The longest-side rule (patternFor(rule, cell))
/// bisects a city's cells across their height once they are about as tall as wide (1.9 x 1 x
/// 1.9: x, z, then y), and every wall below its roof crosses that plane: the bisection copies
/// the walls instead of separating them, spends the reference budget and leaves the leaves
/// large. So of the ten ways to bisect the cell three times (k_x + k_y + k_z = 3 bisections
/// per axis), the one with the least estimated cost, sum over children c of area(c's cell
/// within the node's box) * (references in c) (the surface-area heuristic over the three
/// levels at once; MacDonald & Booth 1990), is taken instead when it makes fewer references
/// than the longest-side rule and costs at least 5 % less. The references come from a sample
/// of the node's triangles classified by their bounding boxes (one side on a plane, as the
/// classifier does; loose triangles go to one child). Where no bisection copies more than
/// another (a scanned mesh's small triangles) the longest-side rule stays. Unseen 400k city
/// (seed 7), per primary ray: 6.7 -> 6.3 nodes, 3.5 -> 2.7 triangle chunks, 123 -> 114 leaf
/// triangles; per shadow ray 1.9 -> 1.4 chunks.
OctreeNode::Pattern patternFor(Rule rule, const BoundingBox3f &cell, const BoundingBox3f &box, const Ref *ids, size_t n) {
    if (rule != Rule::Sah || n == 0) return patternFor(rule, cell);
    // The part of the cell the triangles fill, along each axis.
    float lo[3], hi[3], e[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = std::max(cell.min[a], box.min[a]);
        hi[a] = std::min(cell.max[a], box.max[a]);
        e[a] = cell.max[a] - cell.min[a];
        if (!(hi[a] >= lo[a])) return patternFor(rule, cell);
    }
    // The longest-side rule of the cell.
    int bestK[3] = {};
    {
        const OctreeNode::Pattern byCell = patternFor(rule, cell);
        for (int level = 0; level < 3; ++level) ++bestK[byCell.axis[level]];
    }
    // Below two chunks of triangles the node is a leaf candidate that rarely splits, and the
    // estimate would cost about as much as its classification: the default. (Above it the
    // estimate matters: from 64, the unseen city tests 3.4 instead of 2.7 chunks per primary
    // ray.)
    if (n >= 32) {
        // Per axis and bisection count k: how many of the 2^k slabs of the cell the filled part
        // reaches (one side on a plane, as the classifier decides); their lengths within it add
        // up to hi - lo whatever k.
        double slabs[3][4];
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k <= 3; ++k) {
                int first = 0, last = 0;
                for (int i = 1; i < (1 << k); ++i) {
                    // (times 2^-k: the same float as dividing by 2^k, without a division)
                    const float plane = cell.min[a] + e[a] * float(i) * (1.0f / float(1 << k));
                    first += plane <= lo[a];
                    last += plane < hi[a];
                }
                slabs[a][k] = double(std::max(first, last) - first + 1);
            }
        // Sampled references: the eighth-slabs each one's bounds span along each axis, and
        // the references each candidate (kx, ky, 3 - kx - ky) would make of them, summed. (A
        // sample of 16: the estimate is made for every node and leaf candidate, and must stay
        // small beside their classification; 32 cost the 203k dragon's build 10 %.)
        constexpr size_t kSample = 16;
        const size_t step = std::max<size_t>(1, n / kSample);
        // (Strided over a large node: one cache miss each, so all are requested first.)
        for (size_t i = 0; i < n; i += step) __builtin_prefetch(&ids[i]);
        float scale[3];
        for (int a = 0; a < 3; ++a) scale[a] = e[a] > 0.0f ? 8.0f / e[a] : 0.0f;
        uint32_t copies[4][4] = {};
        for (size_t i = 0; i < n; i += step) {
            const Ref &r = ids[i];
            int span[3][4];
            for (int a = 0; a < 3; ++a) {
                int first = 0, last = 0;
                if (!(r.id & kLooseBit)) {
                    // floor of the lower end, ceil - 1 of the upper end, in [0, 7]
                    const float f = std::min(std::max((r.lo[a] - cell.min[a]) * scale[a], 0.0f), 7.0f);
                    const float g = std::min(std::max((r.hi[a] - cell.min[a]) * scale[a], 0.0f), 8.0f);
                    first = int(f);
                    last = int(g);
                    last -= float(last) == g;
                    last = std::max(last, first);
                }
                for (int k = 0; k <= 3; ++k) span[a][k] = (last >> (3 - k)) - (first >> (3 - k)) + 1;
            }
            for (int kx = 0; kx <= 3; ++kx)
                for (int ky = 0; kx + ky <= 3; ++ky)
                    copies[kx][ky] += uint32_t(span[0][kx] * span[1][ky] * span[2][3 - kx - ky]);
        }
        // Each candidate: the children's areas within the filled part (halved; each child is a
        // product of one reached slab per axis) times the references per reached child.
        const double ex = hi[0] - lo[0], ey = hi[1] - lo[1], ez = hi[2] - lo[2];
        auto estimate = [&](const int k[3]) {
            const double nx = slabs[0][k[0]], ny = slabs[1][k[1]], nz = slabs[2][k[2]];
            return (ex * ey * nz + ey * ez * nx + ex * ez * ny) * double(copies[k[0]][k[1]]) / (nx * ny * nz);
        };
        // The longest-side rule is the default. Another candidate must make fewer references
        // of the triangles (it is chosen to stop copying, never only for smaller children:
        // that is the longest-side rule's work, and on meshes it would change trees for
        // nothing but build time), and beat the default by more than a small sample can tell
        // apart (5 %).
        const uint32_t defaultCopies = copies[bestK[0]][bestK[1]];
        double bestCost = 0.95 * estimate(bestK);
        for (int kx = 0; kx <= 3; ++kx)
            for (int ky = 0; kx + ky <= 3; ++ky) {
                const int k[3] = {kx, ky, 3 - kx - ky};
                const double cost = estimate(k);
                if (cost < bestCost && copies[kx][ky] < defaultCopies) {
                    bestCost = cost;
                    std::copy(k, k + 3, bestK);
                }
            }
    }
    // The chosen bisections in longest-side order (of the filled part), as patternFor(cell).
    OctreeNode::Pattern p{{0, 1, 2}};
    float ext[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    int left[3] = {bestK[0], bestK[1], bestK[2]};
    for (int level = 0; level < 3; ++level) {
        int a = -1;
        for (int b = 0; b < 3; ++b)
            if (left[b] > 0 && (a < 0 || ext[b] > ext[a])) a = b;
        p.axis[level] = uint8_t(a);
        --left[a];
        ext[a] *= 0.5f;
    }
    return p;
}

/// Classifier::mask for the layout of planes of \p k, as a type (see withMask()).
template <int PX, int PY, int PZ, bool OneSide> struct MaskOf {
    const Classifier &k;
    unsigned operator()(const Ref &r) const { return k.maskOf<PX, PY, PZ, OneSide>(r.lo, r.hi); }
};
template <bool OneSide> struct Mask111 {
    const Classifier &k;
    unsigned operator()(const Ref &r) const { return k.mask111<OneSide>(r.lo, r.hi); }
};
struct AnyMask {
    const Classifier &k;
    unsigned operator()(const Ref &r) const { return k.mask(r.lo, r.hi); }
};

/// Run \p body with the mask function of \p k specialised for its planes per axis: the ten
/// layouts of the `sah` rule's three bisections and the classic octants of the other rules
/// (the classification is the build's innermost loop; a generic loop over the planes cost
/// about twice as much).
template <typename Body> void withMask(const Classifier &k, Body &&body) {
    const int key = 100 * k.planes[0] + 10 * k.planes[1] + k.planes[2];
    if (k.oneSide) {
        switch (key) {
        case 111: return body(Mask111<true>{k});
        case 310: return body(MaskOf<3, 1, 0, true>{k});
        case 301: return body(MaskOf<3, 0, 1, true>{k});
        case 130: return body(MaskOf<1, 3, 0, true>{k});
        case 31: return body(MaskOf<0, 3, 1, true>{k});
        case 103: return body(MaskOf<1, 0, 3, true>{k});
        case 13: return body(MaskOf<0, 1, 3, true>{k});
        case 700: return body(MaskOf<7, 0, 0, true>{k});
        case 70: return body(MaskOf<0, 7, 0, true>{k});
        case 7: return body(MaskOf<0, 0, 7, true>{k});
        default: break;
        }
    } else if (key == 111) {
        return body(Mask111<false>{k});
    }
    body(AnyMask{k});
}

std::unique_ptr<TempNode> split(const Input &in, const BoundingBox3f &cell, const BoundingBox3f &box, Ref *ids,
                                size_t n, int depth, double budget);

/// Fill in the counters of \p node from its children (after they are built).
void summarize(TempNode &node) {
    node.subtreeRefs = node.kept.size();
    for (const TempNode::KeptGroup &g : node.keptGroups) node.subtreeWords += TriangleStore::leafWords(g.count);
    node.subtreeGroups = node.keptGroups.empty() ? 0 : node.keptGroups.size() - 1;
    for (int c = 0; c < 8; ++c) {
        if (node.inner[c]) {
            node.subtreeNodes += node.inner[c]->subtreeNodes;
            node.subtreeRefs += node.inner[c]->subtreeRefs;
            node.subtreeWords += node.inner[c]->subtreeWords;
            node.subtreeGroups += node.inner[c]->subtreeGroups;
        } else if (!node.refs[c].empty()) {
            node.subtreeRefs += node.refs[c].size();
            node.subtreeWords += TriangleStore::leafWords(uint32_t(node.refs[c].size()));
        }
    }
}

/// The child cells among \p mask (those the bounding box [lo, hi] touches) that the triangle
/// \p v itself touches. Two candidates with the box inside the cell need no test: the
/// triangle is connected, reaches both closed sides of the plane between them and stays in
/// those two cells, so it touches both. Otherwise a corner inside a cell settles that cell,
/// and the separating-axis test decides the rest.
__attribute__((noinline)) unsigned refine(const std::array<Point3f, 3> &v, const float lo[3], const float hi[3],
                                          const BoundingBox3f &cell, const BoundingBox3f cells[8],
                                          const Classifier &classifier, unsigned mask) {
    bool inside = lo[0] >= cell.min.x() && lo[1] >= cell.min.y() && lo[2] >= cell.min.z() && hi[0] <= cell.max.x() &&
                  hi[1] <= cell.max.y() && hi[2] <= cell.max.z();
    if (inside && __builtin_popcount(mask) == 2) return mask;
    // The cells holding a corner, for all cells at once (the cells' own contains() tests, one
    // per corner and cell, were a third of this function's time).
    unsigned kept = mask & (classifier.cellsHolding(v[0], cell.min, cell.max) |
                            classifier.cellsHolding(v[1], cell.min, cell.max) |
                            classifier.cellsHolding(v[2], cell.min, cell.max));
    unsigned m = mask & ~kept;
    if (!m) return kept;
    // (The triangle's edges and axes once, for all the cells it is tested against.)
    const TriangleBoxTest sat(v[0], v[1], v[2], axisAlignedPlane(v[0], v[1], v[2]));
    for (; m; m &= m - 1) {
        int c = __builtin_ctz(m);
        if (sat.overlaps(cells[c])) kept |= 1u << c;
    }
    return kept ? kept : mask;  // never lose a triangle to rounding
}

/// The boxes a node's triangles are clipped to: its children's cells, and for loose triangles
/// the node's box.
struct Clips {
    Float4 lo[9], hi[9];  ///< 0-7: the child cells; 8: the node's box
    Clips(const BoundingBox3f &box, const BoundingBox3f cells[8]) {
        for (int c = 0; c < 8; ++c) {
            lo[c] = load4(cells[c].min);
            hi[c] = load4(cells[c].max);
        }
        lo[8] = load4(box.min);
        hi[8] = load4(box.max);
    }
};

/// Children's reference counts and tight boxes (the union of their triangles' bounds, each
/// clipped to the child's cell), summed over a run of references.
struct Gathered {
    size_t counts[8] = {};
    Float4 lo[8], hi[8];

    Gathered() {
        for (int c = 0; c < 8; ++c) {
            lo[c] = Float4{} + Infinity;
            hi[c] = Float4{} - Infinity;
        }
    }
    /// Reference \p r goes to the children in \p mask.
    void add(const Ref &r, unsigned mask, const Clips &clips) {
        // (x, y, z, hi.x) and (x, y, z, id): the fourth lanes are never used.
        const Float4 rlo = load4(r.lo), rhi = load4(r.hi);
        // A loose triangle's part that matters lies in this node's box (by induction).
        const bool loose = r.id & kLooseBit;
        for (unsigned m = mask; m; m &= m - 1) {
            int c = __builtin_ctz(m), k = loose ? 8 : c;
            ++counts[c];
            lo[c] = min4(max4(rlo, clips.lo[k]), lo[c]);
            hi[c] = max4(min4(rhi, clips.hi[k]), hi[c]);
        }
    }
    /// add() for a reference that goes to child \p c alone.
    void addOne(const Ref &r, int c, const Clips &clips) {
        const Float4 rlo = load4(r.lo), rhi = load4(r.hi);
        const int k = (r.id & kLooseBit) ? 8 : c;
        ++counts[c];
        lo[c] = min4(max4(rlo, clips.lo[k]), lo[c]);
        hi[c] = max4(min4(rhi, clips.hi[k]), hi[c]);
    }
    /// Add the sums of \p g, a later run (ties keep the earlier bound, as one pass would).
    void merge(const Gathered &g) {
        for (int c = 0; c < 8; ++c) {
            counts[c] += g.counts[c];
            lo[c] = g.lo[c] < lo[c] ? g.lo[c] : lo[c];
            hi[c] = g.hi[c] > hi[c] ? g.hi[c] : hi[c];
        }
    }
    /// The sums of two disjoint sets of references, each summed in order (\p a, \p b), as
    /// one pass over their union in order gives them: the smaller (larger) bound, either
    /// where they are the same float. False where that pass's bound depends on which came
    /// first, a zero of each sign (equal, different bits): then the caller sums in one pass.
    static bool combine(const Gathered &a, const Gathered &b, Gathered &out) {
        const Int4 lanes = {-1, -1, -1, 0};  // the fourth lane is never used
        Int4 ambiguous = {};
        for (int c = 0; c < 8; ++c) {
            Int4 alo, blo, ahi, bhi;
            std::memcpy(&alo, &a.lo[c], sizeof alo);
            std::memcpy(&blo, &b.lo[c], sizeof blo);
            std::memcpy(&ahi, &a.hi[c], sizeof ahi);
            std::memcpy(&bhi, &b.hi[c], sizeof bhi);
            ambiguous |= ((a.lo[c] == b.lo[c]) & (alo != blo)) | ((a.hi[c] == b.hi[c]) & (ahi != bhi));
            out.counts[c] = a.counts[c] + b.counts[c];
            out.lo[c] = b.lo[c] < a.lo[c] ? b.lo[c] : a.lo[c];
            out.hi[c] = b.hi[c] > a.hi[c] ? b.hi[c] : a.hi[c];
        }
        ambiguous &= lanes;
        return !(ambiguous[0] | ambiguous[1] | ambiguous[2]);
    }
    BoundingBox3f box(int c) const { return VecBox{lo[c], hi[c]}.box(); }
    double area(int c) const { return VecBox{lo[c], hi[c]}.area(); }  ///< area(box(c))
};

/// A list of reference indices in a buffer owned elsewhere.
struct Indices {
    uint32_t *data = nullptr;
    size_t count = 0;
    const uint32_t *begin() const { return data; }
    const uint32_t *end() const { return data + count; }
};

/// Split \p refs (the triangles touching \p cell, whose clipped bounds are \p box; a node at
/// \p depth) and recurse. Returns null when the node should stay a leaf.
///
/// Reference budget: the node may hold at most \p budget references below it, and each child
/// inherits the share of it proportional to its references. The root gets kRefBudget (`count`,
/// `seed`) or kSahRefBudget (`sah`) times the triangle count, so no input (needles spanning
/// the box, huge triangles, a vertex fan) makes the tree hold more references per triangle.
/// `count` and `seed` refuse a split beyond the budget; `sah` sends the straddling triangles
/// down loose instead (each into the one child that holds the centre of its bounding box, its
/// child's box grown to hold it whole: a loose octree, Ulrich 2000), which never adds a
/// reference.
std::unique_ptr<TempNode> split(const Input &in, const BoundingBox3f &cellIn, const BoundingBox3f &box, Ref *ids,
                                size_t n, int depth, double budget) {
    const bool sah = in.rule == Rule::Sah;
    BoundingBox3f cell = cellIn;
    OctreeNode::Pattern pattern{{0, 1, 2}};
    BoundingBox3f cells[8];
    // The node's scratch and its children's lists come from this thread's stack arena and go
    // back to it when the node returns (its children, built meanwhile, return theirs first).
    StackArena &arena = StackArena::local();
    struct Release {
        StackArena &arena;
        const StackArena::Mark mark;
        ~Release() { arena.release(mark); }
    } release{arena, arena.mark()};
    // One block for the node's scratch lists: the indices of the straddlers (at most n) and
    // each reference's mask.
    uint32_t *const scratch = arena.allocate<uint32_t>(n + (n + 3) / 4);
    uint8_t *masks = reinterpret_cast<uint8_t *>(scratch + n);
    std::optional<Classifier> classifier;
    Indices straddlers{scratch, 0};  // the references whose bounding boxes straddle, in order

    // Which child cells a triangle touches: its bounding box against the cells (see
    // Classifier::oneSide for a box on a plane), refined by the SAT only for straddling
    // triangles; a loose triangle goes to the cell of its box's centre. \p maskOf: the
    // classifier's mask function (withMask()).
    auto classifyOne = [&](size_t i, auto &&maskOf) {
        const Ref &r = ids[i];
        unsigned mask;
        if (__builtin_expect(r.id & kLooseBit, 0)) {
            mask = 1u << classifier->slotOfCentre(r.lo, r.hi);
        } else {
            mask = maskOf(r);
            if ((mask & (mask - 1)) && in.exact) mask = refine(in.vertices[r.id], r.lo, r.hi, cell, cells, *classifier, mask);
        }
        masks[i] = uint8_t(mask);
        return mask;
    };
    auto classify = [&](size_t i) { return classifyOne(i, AnyMask{*classifier}); };
    // Children's counts and tight boxes over the triangles that go down (mask != 0).
    size_t counts[8];
    BoundingBox3f boxes[8];
    auto setGathered = [&](const Gathered &g) {
        for (int c = 0; c < 8; ++c) {
            counts[c] = g.counts[c];
            boxes[c] = g.box(c);
        }
    };
    auto gather = [&] {
        Gathered g;
        const Clips clips(box, cells);
        for (size_t i = 0; i < n; ++i) g.add(ids[i], masks[i], clips);
        setGathered(g);
    };
    // The sums of the references whose boxes lie in one child are kept apart from those of
    // the straddlers: when some straddlers are kept or go down loose, only those are summed
    // again (Gathered::combine; most of a node's references go to one child).
    Gathered single;
    auto regather = [&] {
        Gathered multi, all;
        const Clips clips(box, cells);
        for (const uint32_t i : straddlers) multi.add(ids[i], masks[i], clips);
        if (Gathered::combine(single, multi, all)) setGathered(all);
        else gather();
    };
    // `sah`: when every triangle lies in one child, the cell shrinks to it (below). Where the
    // triangles' own bounds (and the loose ones' centres) show that at once, the pass over
    // them is skipped: a small object under a huge ground quad would otherwise be classified
    // again at every level of empty space above it (the 400k tabletop: 37 % of all
    // classifications). The bounds are gathered once, only when the node's clipped box lies
    // in one child (they are a superset of it).
    std::optional<std::array<float, 12>> hull;  // bounds' lo, hi; loose centres' lo, hi
    bool anyTight = false, anyLoose = false;
    auto soleChild = [&]() -> int {
        if (!classifier->soleCell(box.min.data(), box.max.data())) return -1;
        if (!hull) {
            Float4 lo = Float4{} + Infinity, hi = Float4{} - Infinity;
            Float4 clo = lo, chi = hi;
            for (size_t i = 0; i < n; ++i) {
                const Ref &r = ids[i];
                const Float4 rlo = load4(r.lo), rhi = load4(r.hi);
                if (r.id & kLooseBit) {
                    // The centre exactly as slotOfCentre() computes it.
                    const Float4 c = 0.5f * (rlo + rhi);
                    clo = min4(c, clo);
                    chi = max4(c, chi);
                    anyLoose = true;
                } else {
                    lo = min4(rlo, lo);
                    hi = max4(rhi, hi);
                    anyTight = true;
                }
            }
            hull.emplace();
            for (int a = 0; a < 3; ++a) {
                (*hull)[a] = lo[a];
                (*hull)[3 + a] = hi[a];
                (*hull)[6 + a] = clo[a];
                (*hull)[9 + a] = chi[a];
            }
        }
        int only = -1;
        if (anyTight) {
            const unsigned m = classifier->soleCell(hull->data(), hull->data() + 3);
            if (!m) return -1;
            only = __builtin_ctz(m);
        }
        if (anyLoose) {
            const int lo = classifier->slotOfPoint(hull->data() + 6), hi = classifier->slotOfPoint(hull->data() + 9);
            if (lo != hi || (only >= 0 && lo != only)) return -1;
            only = lo;
        }
        return only;
    };
    // Shrinking the cell to its only filled child skips a level of empty space. It costs no
    // level of the traversal, and no level of maxDepth either: a small object under a ground
    // 10^9 times its size would otherwise spend every level of maxDepth on the empty space above
    // it and end as one leaf of all its triangles (a 50k-triangle torus 1e-3 across on a
    // ground 2e6 wide: one leaf, 0.15x Embree's primary rays). The cells stay the octree's:
    // each is a half of a half of ... its parent's child cell. A cell whose bisection no longer
    // halves it in float (a few ulps wide) ends the shrinking, so the loop always ends.
    auto shrinkTo = [&](int only) {
        const BoundingBox3f &next = cells[only];
        if (next.min == cell.min && next.max == cell.max) return false;
        cell = next;
        return true;
    };
    for (;;) {
        pattern = patternFor(in.rule, cell, box, ids, n);
        for (int c = 0; c < 8; ++c) cells[c] = cellOf(cell, pattern, c);
        classifier.emplace(cell, pattern, cells, sah);
        if (sah) {
            const int only = soleChild();
            if (only >= 0 && shrinkTo(only)) continue;
        }
        // Classification and gathering in one pass over the references (in blocks of 4096,
        // in parallel for large nodes; the blocks' sums are exact whatever their order).
        withMask(*classifier, [&](auto maskOf) {
            const Clips clips(box, cells);
            // In blocks of kBlock: the bounding-box masks, summing the references that go to
            // one child at once and prefetching the corners of those that straddle (the SAT's
            // cache misses were most of the classification's time; the other triangles'
            // corners are not needed), then the SAT for those and their sums. \p g sums the
            // first kind, \p gm the second, whose indices go to \p multi.
            auto run = [&](size_t begin, size_t end, Gathered &g, Gathered &gm, Indices &multi) {
                uint32_t straddle[kBlock];
                for (size_t b = begin; b < end; b += kBlock) {
                    const size_t e = std::min(end, b + kBlock);
                    size_t k = 0;
                    for (size_t i = b; i < e; ++i) {
                        const Ref &r = ids[i];
                        unsigned mask;
                        if (__builtin_expect(r.id & kLooseBit, 0)) {
                            mask = 1u << classifier->slotOfCentre(r.lo, r.hi);
                        } else {
                            mask = maskOf(r);
                            if (mask & (mask - 1)) {
                                masks[i] = uint8_t(mask);
                                if (in.exact) {
                                    __builtin_prefetch(&in.vertices[r.id]);
                                    __builtin_prefetch(&in.areas[r.id]);  // (for the kept search)
                                    straddle[k++] = uint32_t(i);
                                } else {
                                    gm.add(r, mask, clips);
                                    multi.data[multi.count++] = uint32_t(i);
                                }
                                continue;
                            }
                        }
                        masks[i] = uint8_t(mask);
                        g.addOne(r, __builtin_ctz(mask), clips);
                    }
                    for (size_t j = 0; j < k; ++j) {
                        const uint32_t i = straddle[j];
                        const Ref &r = ids[i];
                        const unsigned mask = refine(in.vertices[r.id], r.lo, r.hi, cell, cells, *classifier, masks[i]);
                        masks[i] = uint8_t(mask);
                        gm.add(r, mask, clips);
                        multi.data[multi.count++] = i;
                    }
                }
            };
            Gathered multi, all;
            single = Gathered();
            straddlers.count = 0;
            if (n > 8 * kParallelRefs) {
                // Block b lists its straddlers from index 4096 b on (it has at most 4096),
                // then the lists close up in order.
                const size_t blocks = (n + 4095) / 4096;
                std::vector<Gathered> parts(2 * blocks);
                std::vector<Indices> multis(blocks);
                tbb::parallel_for(size_t(0), blocks, [&](size_t b) {
                    multis[b] = {straddlers.data + 4096 * b, 0};
                    run(4096 * b, std::min(n, 4096 * b + 4096), parts[2 * b], parts[2 * b + 1], multis[b]);
                });
                for (size_t b = 0; b < blocks; ++b) {
                    single.merge(parts[2 * b]);
                    multi.merge(parts[2 * b + 1]);
                    std::memmove(straddlers.data + straddlers.count, multis[b].data, sizeof(uint32_t) * multis[b].count);
                    straddlers.count += multis[b].count;
                }
            } else {
                run(0, n, single, multi, straddlers);
            }
            if (Gathered::combine(single, multi, all)) setGathered(all);
            else gather();
        });
        // `sah`: every triangle in one and the same child: the split would separate nothing,
        // so the cell shrinks to that child without a node. (Every mask is non-empty, so a
        // child that counts every reference while the counts add up to n holds them all alone.)
        if (!sah) break;
        size_t total = 0;
        int only = -1;
        for (int c = 0; c < 8; ++c) {
            total += counts[c];
            if (counts[c] == n) only = c;
        }
        if (only < 0 || total != n || !shrinkTo(only)) break;
    }
    const double boxArea = area(box);
    auto probability = [&](int c) { return boxArea > 0.0 ? area(boxes[c]) / boxArea : 1.0; };

    // Large triangles stay in the node (`sah`), tested by every ray that reaches it and enters
    // their bounding box (octree_traversal.cpp). In units of the cost model, per triangle t
    // (w: one triangle test, a sixteenth of a chunk):
    //  - copied down, t costs sum over its children c of P(c) * w_c (w_c: t's share of child
    //    c's list, list(n_c) / n_c: w in a list of one chunk, less in a large leaf, whose rays
    //    meet few of its chunks), and a ray that hits t must first descend to one of its
    //    leaves, about D more node visits (D: the levels this subtree will have, log8 of its
    //    chunks); a ray hits t with probability about 2 area(t) / A(node box) (Cauchy: a flat
    //    convex surface's mean projected area);
    //  - kept, t costs w for every ray that reaches the node and enters the kept box.
    // Keeping a set K saves sum over K of sum P(c) * w_c, plus D * kNode for the rays that hit
    // one of K -- with probability at most min(1, sum over K of P(hit t)), since overlapping
    // or stacked triangles are hit by the same rays -- plus the price of the children's boxes
    // that shrink without K's copies (shrink, below), and costs P(K's box) times the kept
    // list (all its chunks, at least one). The candidates (sum P(c) * w_c + P(hit t) * D *
    // kNode > w) are taken in decreasing order of that benefit and the best prefix is kept, if
    // it saves anything: a
    // ground plane under a city or a table, the walls of a room, the backdrop of a studio,
    // never a small triangle of a scanned mesh high in the tree. This is the cost-model form
    // of storing objects at the level that matches their size instead of copying them into
    // every cell (Ulrich 2000, "Loose octrees"; Havran 2000, "Heuristic ray shooting
    // algorithms", 4.4).
    std::vector<uint32_t> kept;
    std::vector<TempNode::KeptGroup> keptGroups;
    double keptPrice = 0.0;  // the cost model's price of the kept groups (the search's, see below)
    if (sah && n > 16) {
        // A candidate's bounding box clipped to the node's box (what lies outside is hit in other cells).
        const Float4 boxLo = load4(box.min), boxHi = load4(box.max);
        auto clippedBox = [&](const Ref &r) { return VecBox::clipped(r.lo, r.hi, boxLo, boxHi); };
        const double w = Cost::kChunk / 16.0;
        const double descent = Cost::levels(n) * Cost::kNode;
        double p[8];
        // A copy in child c costs the rays that enter c its share of c's list (a sixteenth of
        // a chunk in a small list, less in a large leaf, whose rays meet few of its chunks).
        for (int c = 0; c < 8; ++c)
            p[c] = probability(c) * (counts[c] ? Cost::list(counts[c]) / double(counts[c]) / w : 1.0);
        struct Candidate {
            double copies, hit;
            size_t i;
        };
        // (Scratch reused by every node a thread builds: the search ends before the children
        // are built, so a node's search never overlaps another's on one thread.)
        thread_local std::vector<Candidate> candidates;
        candidates.clear();
        // The children's boxes over what goes down in any case: every reference but the
        // candidates (see shrink below).
        const Clips clips(box, cells);
        Gathered stays = single;
        for (const uint32_t i : straddlers) {
            unsigned m = masks[i];
            if (m & (m - 1)) {
                double copies = 0.0;
                for (; m; m &= m - 1) copies += p[__builtin_ctz(m)];
                // (A dense array: the corners of a random triangle cost three cache lines.)
                double hit = boxArea > 0.0 ? std::min(1.0, double(in.areas[ids[i].id & ~kLooseBit]) / boxArea) : 0.0;
                if (copies * w + hit * descent > w) {
                    candidates.push_back({copies * w, hit, i});
                    continue;
                }
            }
            stays.add(ids[i], masks[i], clips);
        }
        std::sort(candidates.begin(), candidates.end(), [&](const Candidate &a, const Candidate &b) {
            return a.copies + a.hit * descent > b.copies + b.hit * descent;
        });
        const size_t searched = std::min<size_t>(candidates.size(), OctreeNode::kKeptMask);
        // A candidate sent down also stretches the boxes of the children it goes to, and every
        // ray that enters a stretched box pays for the child's other content: a wall through
        // the root's children grows one from the furniture's bounds to its whole cell
        // (bench/README.md, forty-third round). shrink[k]: the children's boxes' price with
        // candidates 0..k-1 kept and the rest down, each box at the chance that a ray enters
        // it times what its content costs once entered (a list, or for a larger child the
        // levels of its subtree and one chunk).
        thread_local std::vector<double> shrink;
        shrink.assign(searched + 1, 0.0);
        if (searched > 0 && boxArea > 0.0) {
            for (size_t k = searched; k < candidates.size(); ++k) stays.add(ids[candidates[k].i], masks[candidates[k].i], clips);
            double content[8], boxPrice[8], price = 0.0;
            Gathered down = stays;
            for (int c = 0; c < 8; ++c) {
                content[c] = std::min(Cost::list(counts[c]), Cost::levels(counts[c]) * Cost::kNode + Cost::kChunk) / boxArea;
                boxPrice[c] = down.area(c) * content[c];
                price += boxPrice[c];
            }
            shrink[searched] = price;
            for (size_t k = searched; k-- > 0;) {
                const unsigned m = masks[candidates[k].i];
                down.add(ids[candidates[k].i], m, clips);
                for (unsigned b = m; b; b &= b - 1) {
                    const int c = __builtin_ctz(b);
                    const double now = down.area(c) * content[c];
                    price += now - boxPrice[c];
                    boxPrice[c] = now;
                }
                shrink[k] = price;
            }
        }
        double copies = 0.0, hit = 0.0, bestSaving = 0.0, keptCost = 0.0;
        size_t best = 0;
        bool bestSingle = false;
        // Only rays that enter a group's box test its list, so the kept triangles form up to
        // kMaxGroups groups with boxes of their own: each candidate joins the group whose cost
        // (P(box) times its list, plus the box test) grows least, or starts a group where
        // that costs less (a ground and a light quad far above it, a floor and a far wall:
        // one box around both would fill the node's box, tested by every ray). That choice
        // is greedy: once one box fills the node's, more triangles cost nothing up to a full
        // chunk (the walls of a closed box: one chunk for all six beats six small groups), so
        // each prefix is also priced as one group, and the better of the two counts; separate
        // groups only where they cost less than kGroupMargin times one group. A prefix
        // that still costs more than it saves loses to a shorter one; the rest go down and
        // may be kept lower, in boxes of their own.
        VecBox prefixBox;
        struct Group {
            VecBox box;  ///< bounds of its triangles, clipped to the node's box
            size_t n = 0;
            double cost = 0.0;
        };
        Group groups[OctreeKept::kMaxGroups];
        int groupCount = 0;
        thread_local std::vector<uint8_t> groupOf;
        groupOf.assign(candidates.size(), 0);
        auto groupCost = [&](const VecBox &b, size_t count) {
            return (boxArea > 0.0 ? std::min(1.0, b.area() / boxArea) : 1.0) * Cost::list(count);
        };
        for (size_t k = 0; k < searched; ++k) {
            copies += candidates[k].copies;
            hit += candidates[k].hit;
            const Ref &r = ids[candidates[k].i];
            const VecBox b = clippedBox(r);
            int choice = groupCount;
            double delta = groupCount < OctreeKept::kMaxGroups ? groupCost(b, 1) : Infinity, choiceCost = delta;
            if (groupCount > 0) delta += kKeptBoxCost;  // a further group's box test
            VecBox choiceBox = b;
            for (int g = 0; g < groupCount; ++g) {
                VecBox joined = groups[g].box;
                joined.expandBy(b);
                const double c = groupCost(joined, groups[g].n + 1);
                if (c - groups[g].cost <= delta) {
                    delta = c - groups[g].cost;
                    choice = g;
                    choiceCost = c;
                    choiceBox = joined;
                }
            }
            if (choice == groupCount) ++groupCount;
            groups[choice].box = choiceBox;
            groups[choice].n += 1;
            groups[choice].cost = choiceCost;
            groupOf[k] = uint8_t(choice);
            keptCost += delta;
            prefixBox.expandBy(b);
            const double singleCost = groupCost(prefixBox, k + 1);
            const bool single = kGroupMargin * singleCost <= keptCost;
            double saving = copies + std::min(1.0, hit) * descent + (shrink[0] - shrink[k + 1]) - (single ? singleCost : keptCost);
            if (saving > bestSaving + 1e-9) {
                bestSaving = saving;
                best = k + 1;
                bestSingle = single;
            }
        }
        if (bestSingle) std::fill(groupOf.begin(), groupOf.end(), uint8_t(0));
        // The price of the groups the search formed (their boxes' chance to be entered times
        // their lists, plus the further boxes' tests): the node's leaf-or-split decision below.
        {
            VecBox groupBox[OctreeKept::kMaxGroups];
            size_t groupSize[OctreeKept::kMaxGroups] = {};
            for (size_t k = 0; k < best; ++k) {
                const Ref &r = ids[candidates[k].i];
                groupBox[groupOf[k]].expandBy(clippedBox(r));
                ++groupSize[groupOf[k]];
            }
            int used = 0;
            for (int g = 0; g < OctreeKept::kMaxGroups; ++g)
                if (groupSize[g]) ++used, keptPrice += groupCost(groupBox[g], groupSize[g]);
            if (used > 1) keptPrice += kKeptBoxCost * double(used - 1);
        }
        // The node and its kept groups alone cost more than the leaf: the leaf-or-split rule
        // below returns null whatever the children cost (they only add to the split's price,
        // and the lookahead's least price is at least this much too), so the node ends here,
        // before its kept list is written out and its children summed again. Stacked
        // triangles that each cross the node's whole box reach this at every depth-3 node of
        // the tilted slats (bench/README.md, forty-fifth round). (The margin covers the
        // rounding of the sums below, so the trees are exactly those of the full rule.)
        if (Cost::kNode + keptPrice > Cost::list(n) * (1.0 + 1e-9)) return nullptr;
        // Where every kept triangle lies in an axis-aligned plane on the shell of the node's box
        // (a storey's floor and ceiling, a room's walls, a ground and a light above it), they
        // are grouped by plane instead, one group per face of the box. Such a group's box is
        // flat: a ray enters it exactly where it meets the plane, so the closest-hit traversal
        // tests it in its turn among the node's children and culls it behind a nearer hit
        // (the content inside the shell lies in front of the far faces), and a ray that does
        // not cross the plane within the group's extent never tests it. One box around the
        // faces is the node's own, entered first by every ray. The isotropic model above
        // cannot see that (it counts no ray that stops before a plane, and prices a floor and
        // a ceiling 3 m apart lower in one box than in two), so the node keeps the search's
        // price. Planes inside the box (the faces of a tower's fins) stay as the search
        // grouped them: their groups only multiplied the box and list tests of any-hit rays,
        // and the slots of the folded tree's wide nodes (bench/README.md, seventeenth round).
        static_assert(OctreeKept::kMaxGroups >= 6, "a group for each face of a node's box");
        if (best > 1) {
            int planeAxis[6];
            float planeAt[6];
            int planes = 0;
            thread_local std::vector<uint8_t> byPlane;
            byPlane.assign(best, 0);
            size_t k = 0;
            for (; k < best; ++k) {
                const Ref &r = ids[candidates[k].i];
                const int a = r.lo[0] == r.hi[0] ? 0 : r.lo[1] == r.hi[1] ? 1 : r.lo[2] == r.hi[2] ? 2 : -1;
                if (a < 0) break;
                if (r.lo[a] != box.min[a] && r.lo[a] != box.max[a]) break;  // not on the node box's shell
                int g = 0;
                while (g < planes && !(planeAxis[g] == a && planeAt[g] == r.lo[a])) ++g;
                if (g == planes) {  // (at most six: the faces of the box)
                    planeAxis[planes] = a;
                    planeAt[planes] = r.lo[a];
                    ++planes;
                }
                byPlane[k] = uint8_t(g);
            }
            if (k == best) std::copy(byPlane.begin(), byPlane.end(), groupOf.begin());
        }
        if (best > 0) {
            // The best prefix's groups, in the order they were started (a group that only a
            // later candidate started is left out), each box clipped to the node's box as the
            // children's are to their cells: what lies outside is hit in other cells.
            int used = 0;
            for (size_t k = 0; k < best; ++k) used = std::max(used, int(groupOf[k]) + 1);
            kept.reserve(best);
            for (int g = 0; g < used; ++g) {
                VecBox groupBox;
                uint32_t count = 0;
                for (size_t k = 0; k < best; ++k) {
                    if (groupOf[k] != g) continue;
                    const Ref &r = ids[candidates[k].i];
                    kept.push_back(r.id & ~kLooseBit);
                    groupBox.expandBy(clippedBox(r));
                    masks[candidates[k].i] = 0;
                    ++count;
                }
                keptGroups.push_back({count, groupBox.box()});
            }
            regather();
        }
    }

    size_t down = n - kept.size(), sumDown = 0, largest = 0;
    for (size_t c : counts) {
        sumDown += c;
        largest = std::max(largest, c);
    }
    if (double(sumDown + kept.size()) > budget) {
        if (!sah) return nullptr;
        // Over budget: the straddling triangles go down loose.
        for (const uint32_t i : straddlers)
            if (masks[i] & (masks[i] - 1)) {  // (not kept)
                ids[i].id |= kLooseBit;
                classify(i);
            }
        regather();
        sumDown = down;
    }
    const size_t sum = sumDown + kept.size();
    bool speculative = false;              // a split the greedy rule rejected (see below)
    double childScale = 1.0, leafCost = 0.0;
    if (sah) {
        // Leaf or split, by the cost model (greedy: the children are priced as leaves).
        double cost = Cost::kNode + keptPrice;
        double children = 0.0, entries = 0.0;
        for (int c = 0; c < 8; ++c) {
            children += probability(c) * Cost::list(counts[c]);
            entries += probability(c);
        }
        const double leaf = Cost::list(n);
        // Termination (Ize & Hansen 2011, "RTSAH Traversal Order for Occlusion Rays"): the
        // traversal visits the children front to back and culls those beyond the closest hit,
        // so a ray that passes through several children (entries > 1 on average) often stops
        // in the first it enters. A child visited after another is reached only if the ray
        // missed that other child's triangles: opacity alpha_c = 1 - exp(-h_c), h_c the
        // expected hits of a ray entering c's box (a triangle of area a: 2a / A(box), its
        // area shared among the children it is copied into). Priced only where it could turn
        // a leaf into a split.
        const double later = entries > 1.0 ? (entries - 1.0) / entries : 0.0;
        const double priced = children;  // (before the termination discount)
        if (in.termination && cost + children >= leaf && cost + children * (1.0 - later) < leaf) {
            double hits[8] = {};
            for (size_t i = 0; i < n; ++i) {
                const unsigned m = masks[i];
                if (!m) continue;  // kept
                const double a = double(in.areas[ids[i].id & ~kLooseBit]) / double(__builtin_popcount(m));
                for (unsigned k = m; k; k &= k - 1) hits[__builtin_ctz(k)] += a;
            }
            double opaque = 0.0;
            for (int c = 0; c < 8; ++c) {
                const double a = area(boxes[c]);
                if (a > 0.0) opaque += probability(c) * (1.0 - std::exp(-hits[c] / a));
            }
            children *= 1.0 - later * opaque / entries;
        }
        childScale = priced > 0.0 ? children / priced : 1.0;
        cost += children;
        if (cost >= leaf) {
            // The greedy rule prices every child as a leaf. Where one child alone, at that
            // price, makes the split lose, the child is nearly the node itself (the pebbles of
            // a clutter scene: one child with 1078 of 1096 references in 0.99 of the box), and
            // its own split may well pay. Then the split is built anyway if it would win with
            // that child at its least price (one node and one chunk), and kept only if the
            // subtree's cost, computed bottom up, beats the leaf (below).
            int big = 0;
            for (int c = 1; c < 8; ++c)
                if (probability(c) * Cost::list(counts[c]) > probability(big) * Cost::list(counts[big])) big = c;
            const double bigPrice = probability(big) * Cost::list(counts[big]) * childScale;
            const double least = cost - bigPrice + probability(big) * (Cost::kNode + Cost::kChunk) * childScale;
            const bool nearlyTheNode = Cost::kNode + keptPrice + bigPrice >= leaf;
            if (!in.lookahead || !nearlyTheNode || counts[big] < in.leafSize || depth + 1 >= in.maxDepth || least >= leaf)
                return nullptr;
            speculative = true;
            leafCost = leaf;
        }
    } else if (in.rule == Rule::Count && (sumDown > 4 * down || (largest == down && sumDown >= 2 * down))) {
        // No progress: the triangles are mostly larger than the children (each lands in more
        // than half of them), or the fullest child keeps every triangle while many straddle
        // (a vertex fan, stacked identical triangles): splitting again would only multiply
        // references. The seed's rule has no such test; it ends at maxDepth and the budget.
        return nullptr;
    }

    auto node = std::make_unique<TempNode>();
    node->pattern = pattern;
    node->kept = std::move(kept);
    node->keptGroups = std::move(keptGroups);
    // The children's lists, one after the other in one block.
    size_t start[9] = {};
    for (int c = 0; c < 8; ++c) {
        start[c + 1] = start[c] + counts[c];
        node->box[c] = boxes[c];
    }
    Ref *const lists = arena.allocate<Ref>(start[8]);
    {
        Ref *out[8];
        for (int c = 0; c < 8; ++c) out[c] = lists + start[c];
        // Between two straddlers every reference goes to one child (its box lies in it); the
        // straddlers go to all of theirs (none when kept).
        size_t i = 0;
        for (const uint32_t next : straddlers) {
            for (; i < next; ++i) *out[__builtin_ctz(masks[i])]++ = ids[i];
            for (unsigned m = masks[i]; m; m &= m - 1) *out[__builtin_ctz(m)]++ = ids[i];
            ++i;
        }
        for (; i < n; ++i) *out[__builtin_ctz(masks[i])]++ = ids[i];
    }

    // Depth of each child: one level below, or for the seed's rule one more level for every
    // earlier sibling (its build passes `++ctr` to the children in turn, empty ones included).
    for (int c = 0; c < 8; ++c) node->childDepth[c] = depth + 1 + (in.rule == Rule::Seed ? c : 0);

    auto buildChild = [&](int c) {
        Ref *list = lists + start[c];
        const size_t size = counts[c];
        if (size >= in.leafSize && node->childDepth[c] < in.maxDepth) {
            double share = budget * double(size) / double(sum);
            std::unique_ptr<TempNode> sub = split(in, cells[c], node->box[c], list, size, node->childDepth[c], share);
            if (sub) node->inner[c] = std::move(sub);
        }
    };
    if (n > kParallelRefs) {
        tbb::task_group group;
        for (int c = 0; c < 8; ++c) group.run([&, c] { buildChild(c); });
        group.wait();
    } else {
        for (int c = 0; c < 8; ++c) buildChild(c);
    }
    if (sah) {
        // The subtree's price as the cost model makes it, bottom up: the children's own
        // subtrees where they split.
        double children = 0.0;
        for (int c = 0; c < 8; ++c)
            children += probability(c) * (node->inner[c] ? node->inner[c]->cost : Cost::list(counts[c]));
        node->cost = Cost::kNode + keptPrice + children * childScale;
        if (speculative && node->cost >= leafCost) return nullptr;
    }
    // The leaves' ids, without loose marks, in one block for all the node's leaves.
    size_t leafRefs = 0;
    for (int c = 0; c < 8; ++c)
        if (!node->inner[c]) leafRefs += counts[c];
    if (leafRefs) {
        node->leafIds = makeLargeArray<uint32_t>(leafRefs);
        uint32_t *out = node->leafIds.get();
        for (int c = 0; c < 8; ++c) {
            if (node->inner[c] || !counts[c]) continue;
            const Ref *list = lists + start[c];
            for (size_t i = 0; i < counts[c]; ++i) out[i] = list[i].id & ~kLooseBit;
            node->refs[c] = {out, counts[c]};
            out += counts[c];
        }
    }
    summarize(*node);
    return node;
}

} // namespace

OctreeNode::Pattern splitPattern(OctreeAccel::BuildRule rule, const BoundingBox3f &cell) { return patternFor(rule, cell); }

BoundingBox3f childCell(const BoundingBox3f &cell, const OctreeNode::Pattern &p, int c) { return cellOf(cell, p, c); }

OctreeNode::Pattern splitPattern(OctreeAccel::BuildRule rule, const BoundingBox3f &cell, const BoundingBox3f &box,
                                 const std::vector<BoundingBox3f> &bounds) {
    std::vector<Ref> refs(bounds.size());
    for (size_t i = 0; i < bounds.size(); ++i)
        refs[i] = {{bounds[i].min.x(), bounds[i].min.y(), bounds[i].min.z()},
                   {bounds[i].max.x(), bounds[i].max.y(), bounds[i].max.z()}, uint32_t(i)};
    return patternFor(rule, cell, box, refs.data(), refs.size());
}

std::unique_ptr<TempNode> subdivide(const Input &in, const BoundingBox3f &cell, const BoundingBox3f &box, Ref *refs,
                                    size_t n) {
    if (n < in.leafSize || in.maxDepth <= 0) return nullptr;
    double perTriangle = in.rule == Rule::Sah ? kSahRefBudget : kRefBudget;
    return split(in, cell, box, refs, n, 0, perTriangle * double(n));
}

} // namespace nori::octree_build
