/// \file octree_traversal.cpp
/// \brief Octree traversals: simd (default, exact), sorted (exact), seed (inexact, for comparison).
#include "octree.h"
#include <algorithm>
#include <cmath>

#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512DQ__)
#include <immintrin.h>
#define NORI_OCTREE_AVX512 1
#elif defined(__AVX2__)
#include <immintrin.h>
#define NORI_OCTREE_AVX2 1
#endif

namespace nori {
#ifdef NORI_OCTREE_COUNTERS
OctreeCounters g_octreeCounters;
#define NORI_OCTREE_COUNT(field, n) (g_octreeCounters.field += (n))
#else
#define NORI_OCTREE_COUNT(field, n) ((void)0)
#endif

namespace {

/// Child slab distances are widened by this relative amount (entry rounded down, exit up),
/// which covers the rounding of (plane - origin) * (1 / d) (Ize 2013, "Robust BVH Ray
/// Traversal"): a box is never culled for a ray that touches it.
constexpr float kSlabEps = 0x1p-20f;

/// Enough for the deepest tree: at most seven siblings wait per level.
constexpr int kStackSize = 8 * (OctreeAccel::kMaxDepthLimit + 1);

/// Per-ray data of the scalar child box test.
struct SlabRay {
    float o[3], rcpNear[3], rcpFar[3];
    int neg[3];  ///< 1 where the direction's sign bit is set: the entry plane is the box's upper bound
    unsigned signs;  ///< bit a = neg[a]

    explicit SlabRay(const Ray3f &ray) {
        signs = 0;
        for (int a = 0; a < 3; ++a) {
            o[a] = ray.o[a];
            neg[a] = std::signbit(ray.d[a]) ? 1 : 0;
            rcpNear[a] = ray.dRcp[a] * (1.0f - kSlabEps);
            rcpFar[a] = ray.dRcp[a] * (1.0f + kSlabEps);
            signs |= unsigned(neg[a]) << a;
        }
    }

    /// The ray's octant for a node with pattern \p code: bit 2 - l is the sign of the
    /// direction along the node's bisection axis l (see OctreeNode::Pattern).
    unsigned octant(uint32_t code) const { return kOctants[code][signs]; }

    /// kOctants[code][signs], for every pattern code.
    struct OctantTable {
        uint8_t o[64][8];
        OctantTable() {
            for (uint32_t code = 0; code < 64; ++code)
                for (unsigned sg = 0; sg < 8; ++sg) {
                    OctreeNode::Pattern p = OctreeNode::Pattern::fromCode(code);
                    unsigned oct = 0;
                    for (int l = 0; l < 3; ++l) oct |= ((sg >> (p.axis[l] & 3u)) & 1u) << (2 - l);
                    o[code][sg] = uint8_t(oct);
                }
        }
        const uint8_t *operator[](uint32_t code) const { return o[code]; }
    };
    static const OctantTable kOctants;

    /// Entry distance into child \p c of \p node if the ray meets it within [mint, maxt].
    /// A NaN (origin on a slab plane of a direction component that is zero) never narrows
    /// the interval.
    bool hit(const OctreeNode &node, int c, float mint, float maxt, float &tnear) const {
        float t0 = mint, t1 = maxt;
        for (int a = 0; a < 3; ++a) {
            float lo = node.box[a][c + 8 * neg[a]], hi = node.box[a][c + 8 * (1 - neg[a])];
            float tn = (lo - o[a]) * rcpNear[a], tf = (hi - o[a]) * rcpFar[a];
            t0 = tn > t0 ? tn : t0;
            t1 = tf < t1 ? tf : t1;
        }
        tnear = t0;
        return t0 <= t1;
    }
};

const SlabRay::OctantTable SlabRay::kOctants;

/// Pattern code of an inner-node reference.
inline uint32_t patternOf(uint32_t ref) { return (ref >> OctreeNode::kPatternShift) & 63u; }

struct StackEntry {
    uint32_t child, count;  ///< as in OctreeNode
    float tnear;
};

#if NORI_OCTREE_AVX512
/// Per-ray data of the 8-box AVX-512 test. Lane j < 8 gets the entry plane of child
/// (7 - j) ^ octant, lane 8 + j its exit plane, so the lanes come out in the ray's back-to-front
/// order (pushed onto the stack in that order, the nearest child ends up on top). Exit lanes
/// are negated so that one max accumulates entry distances (lanes 0-7) and minus exit
/// distances (lanes 8-15) at once.
struct SimdRay {
    __m512 org[3], scale[3];
    __m512i flip[3];  ///< per axis: 8 in the lanes that read the box's upper half
    unsigned signs;

    explicit SimdRay(const SlabRay &s) : signs(s.signs) {
        for (int a = 0; a < 3; ++a) {
            org[a] = _mm512_set1_ps(s.o[a]);
            scale[a] = _mm512_mask_blend_ps(0xFF00, _mm512_set1_ps(s.rcpNear[a]), _mm512_set1_ps(-s.rcpFar[a]));
            flip[a] = _mm512_mask_blend_epi32(0xFF00, _mm512_set1_epi32(8 * s.neg[a]), _mm512_set1_epi32(8 - 8 * s.neg[a]));
        }
    }
    static __m512 interval(float mint, float maxt) {
        return _mm512_mask_blend_ps(0xFF00, _mm512_set1_ps(mint), _mm512_set1_ps(-maxt));
    }
    /// Push the children of \p node (reached through a reference with pattern \p code) that the
    /// ray enters within the interval onto the stack (farthest first) with their entry
    /// distances; returns how many. Register compress plus a full store: a compress straight
    /// to memory is slow on some cores.
    int push(const OctreeNode &node, uint32_t code, __m512 interval, uint32_t *child, uint32_t *count,
             float *tnear) const {
        const __m512i back = _mm512_set_epi32(0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 2, 3, 4, 5, 6, 7);
        __m512i order = _mm512_xor_si512(back, _mm512_set1_epi32(int(SlabRay::kOctants[code][signs])));
        __m512 acc = interval;
        for (int a = 0; a < 3; ++a) {
            __m512 planes = _mm512_permutexvar_ps(_mm512_xor_si512(order, flip[a]), _mm512_load_ps(node.box[a]));
            __m512 t = _mm512_mul_ps(_mm512_sub_ps(planes, org[a]), scale[a]);
            acc = _mm512_max_ps(t, acc);  // vmaxps returns the second operand on NaN
        }
        __m256 entry = _mm512_castps512_ps256(acc);
        __m256 exit = _mm256_xor_ps(_mm512_extractf32x8_ps(acc, 1), _mm256_set1_ps(-0.0f));
        __mmask8 mask = _mm256_cmp_ps_mask(entry, exit, _CMP_LE_OQ);
        __m256i childOrder = _mm512_castsi512_si256(order);
        __m256i c = _mm256_permutexvar_epi32(childOrder, _mm256_load_si256(reinterpret_cast<const __m256i *>(node.child)));
        __m256i n = _mm256_permutexvar_epi32(childOrder, _mm256_load_si256(reinterpret_cast<const __m256i *>(node.count)));
        _mm256_storeu_si256(reinterpret_cast<__m256i *>(child), _mm256_maskz_compress_epi32(mask, c));
        _mm256_storeu_si256(reinterpret_cast<__m256i *>(count), _mm256_maskz_compress_epi32(mask, n));
        _mm256_storeu_ps(tnear, _mm256_maskz_compress_ps(mask, entry));
        return __builtin_popcount(mask);
    }
};
#elif NORI_OCTREE_AVX2
/// The 8-box test with AVX2: one lane per child, permuted into the ray's back-to-front octant
/// order; the surviving lanes are packed onto the stack by a short scalar loop (AVX2 has no
/// compress instruction).
struct SimdRay {
    __m256 org[3], rcpNear[3], rcpFar[3];
    int neg[3];
    unsigned signs;

    explicit SimdRay(const SlabRay &s) : signs(s.signs) {
        for (int a = 0; a < 3; ++a) {
            org[a] = _mm256_set1_ps(s.o[a]);
            rcpNear[a] = _mm256_set1_ps(s.rcpNear[a]);
            rcpFar[a] = _mm256_set1_ps(s.rcpFar[a]);
            neg[a] = s.neg[a];
        }
    }
    struct Interval {
        __m256 mint, maxt;
    };
    static Interval interval(float mint, float maxt) { return {_mm256_set1_ps(mint), _mm256_set1_ps(maxt)}; }
    int push(const OctreeNode &node, uint32_t code, Interval iv, uint32_t *child, uint32_t *count, float *tnear) const {
        const unsigned octant = SlabRay::kOctants[code][signs];
        const __m256i perm = _mm256_xor_si256(_mm256_setr_epi32(7, 6, 5, 4, 3, 2, 1, 0), _mm256_set1_epi32(int(octant)));
        __m256 t0 = iv.mint, t1 = iv.maxt;
        for (int a = 0; a < 3; ++a) {
            const float *box = node.box[a];
            __m256 nearPlane = _mm256_permutevar8x32_ps(_mm256_load_ps(box + 8 * neg[a]), perm);
            __m256 farPlane = _mm256_permutevar8x32_ps(_mm256_load_ps(box + 8 * (1 - neg[a])), perm);
            __m256 tn = _mm256_mul_ps(_mm256_sub_ps(nearPlane, org[a]), rcpNear[a]);
            __m256 tf = _mm256_mul_ps(_mm256_sub_ps(farPlane, org[a]), rcpFar[a]);
            t0 = _mm256_max_ps(tn, t0);  // second operand on NaN: a NaN never narrows the interval
            t1 = _mm256_min_ps(tf, t1);
        }
        unsigned mask = unsigned(_mm256_movemask_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OQ)));
        alignas(32) float entry[8];
        _mm256_store_ps(entry, t0);
        int k = 0;
        for (; mask; mask &= mask - 1) {
            int j = __builtin_ctz(mask);
            int c = int(unsigned(7 - j) ^ octant);
            child[k] = node.child[c];
            count[k] = node.count[c];
            tnear[k++] = entry[j];
        }
        return k;
    }
};
#else
/// Portable stand-in with the same lane order.
struct SimdRay {
    const SlabRay &slab;
    explicit SimdRay(const SlabRay &s) : slab(s) {}
    struct Interval { float mint, maxt; };
    static Interval interval(float mint, float maxt) { return {mint, maxt}; }
    int push(const OctreeNode &node, uint32_t code, Interval iv, uint32_t *child, uint32_t *count, float *tnear) const {
        const unsigned octant = slab.octant(code);
        int k = 0;
        for (int j = 7; j >= 0; --j) {
            int c = int(unsigned(j) ^ octant);
            if (slab.hit(node, c, iv.mint, iv.maxt, tnear[k])) {
                child[k] = node.child[c];
                count[k++] = node.count[c];
            }
        }
        return k;
    }
};
#endif

} // namespace

// ---------------------------------------------------------------------------------------------
// simd: one 8-box test per node, children in the ray's octant order. For the midpoint split,
// child index XOR the direction's sign bits orders the cells front to back (Revelles et al.
// 2000's observation); the order only affects speed, exactness comes from culling every
// entry beyond the closest hit found so far and never stopping early.

bool OctreeAccel::intersectSimd(const Ray3f &ray, Hit &hit) const {
    const SlabRay slab(ray);
    const SimdRay simd(slab);
    const TriangleRay tri(ray);
    Hit best;
    best.t = ray.maxt;
    auto interval = SimdRay::interval(ray.mint, best.t);

    // Structure-of-arrays stack, with room for a full 8-lane store past the top.
    alignas(32) uint32_t stackChild[kStackSize + 8], stackCount[kStackSize + 8];
    alignas(32) float stackT[kStackSize + 8];
    stackChild[0] = 0;
    stackCount[0] = m_rootCount;
    stackT[0] = ray.mint;
    int sp = 1;
    while (sp > 0) {
        --sp;
        if (stackT[sp] > best.t) continue;  // entered only beyond the closest hit so far
        uint32_t child = stackChild[sp], count = stackCount[sp];
        if (count & OctreeNode::kInner) {
            uint32_t kept = count & OctreeNode::kKeptMask;  // the node's own large triangles first
            NORI_OCTREE_COUNT(nodes, 1);
            NORI_OCTREE_COUNT(keptTris, kept);
            if (kept && m_triangles.intersect(tri, m_keptOffset[child], kept, best))
                interval = SimdRay::interval(ray.mint, best.t);
            sp += simd.push(m_nodes[child], patternOf(count), interval, stackChild + sp, stackCount + sp, stackT + sp);
        } else {
            NORI_OCTREE_COUNT(leaves, 1);
            NORI_OCTREE_COUNT(leafTris, count);
            if (m_triangles.intersect(tri, child, count, best)) interval = SimdRay::interval(ray.mint, best.t);
        }
    }
    if (best.prim == ~0u) return false;
    hit = best;
    return true;
}

bool OctreeAccel::occludedSimd(const Ray3f &ray) const {
    const SlabRay slab(ray);
    const SimdRay simd(slab);
    const TriangleRay tri(ray);
    const auto interval = SimdRay::interval(ray.mint, ray.maxt);

    alignas(32) uint32_t stackChild[kStackSize + 8], stackCount[kStackSize + 8];
    alignas(32) float stackT[kStackSize + 8];
    stackChild[0] = 0;
    stackCount[0] = m_rootCount;
    int sp = 1;
    while (sp > 0) {
        --sp;
        uint32_t child = stackChild[sp], count = stackCount[sp];
        if (count & OctreeNode::kInner) {
            uint32_t kept = count & OctreeNode::kKeptMask;
            NORI_OCTREE_COUNT(nodes, 1);
            NORI_OCTREE_COUNT(keptTris, kept);
            if (kept && m_triangles.occluded(tri, m_keptOffset[child], kept, ray.maxt)) return true;
            sp += simd.push(m_nodes[child], patternOf(count), interval, stackChild + sp, stackCount + sp, stackT + sp);
        } else {
            NORI_OCTREE_COUNT(leaves, 1);
            NORI_OCTREE_COUNT(leafTris, count);
            if (m_triangles.occluded(tri, child, count, ray.maxt)) return true;
        }
    }
    return false;
}

// ---------------------------------------------------------------------------------------------
// sorted: scalar box tests, children sorted by entry distance, cull entries beyond the best hit.

namespace {
/// Hit children of \p node sorted by entry distance, nearest first; returns how many.
int sortedChildren(const OctreeNode &node, const SlabRay &slab, float mint, float maxt, int order[8],
                   float tnear[8]) {
    int n = 0;
    for (int c = 0; c < 8; ++c) {
        float t;
        if (!slab.hit(node, c, mint, maxt, t)) continue;
        int k = n++;
        for (; k > 0 && tnear[k - 1] > t; --k) {  // insertion sort
            tnear[k] = tnear[k - 1];
            order[k] = order[k - 1];
        }
        tnear[k] = t;
        order[k] = c;
    }
    return n;
}
} // namespace

bool OctreeAccel::intersectSorted(const Ray3f &ray, Hit &hit) const {
    const SlabRay slab(ray);
    const TriangleRay tri(ray);
    Hit best;
    best.t = ray.maxt;
    StackEntry stack[kStackSize];
    int sp = 0;
    stack[sp++] = {0, m_rootCount, ray.mint};
    while (sp > 0) {
        StackEntry e = stack[--sp];
        if (e.tnear > best.t) continue;
        if (!(e.count & OctreeNode::kInner)) {
            m_triangles.intersect(tri, e.child, e.count, best);
            continue;
        }
        if (uint32_t kept = e.count & OctreeNode::kKeptMask) m_triangles.intersect(tri, m_keptOffset[e.child], kept, best);
        const OctreeNode &node = m_nodes[e.child];
        int order[8];
        float tnear[8];
        int n = sortedChildren(node, slab, ray.mint, best.t, order, tnear);
        for (int k = n - 1; k >= 0; --k)
            stack[sp++] = {node.child[order[k]], node.count[order[k]], tnear[k]};
    }
    if (best.prim == ~0u) return false;
    hit = best;
    return true;
}

bool OctreeAccel::occludedSorted(const Ray3f &ray) const {
    const SlabRay slab(ray);
    const TriangleRay tri(ray);
    StackEntry stack[kStackSize];
    int sp = 0;
    stack[sp++] = {0, m_rootCount, ray.mint};
    while (sp > 0) {
        StackEntry e = stack[--sp];
        if (!(e.count & OctreeNode::kInner)) {
            if (m_triangles.occluded(tri, e.child, e.count, ray.maxt)) return true;
            continue;
        }
        uint32_t kept = e.count & OctreeNode::kKeptMask;
        if (kept && m_triangles.occluded(tri, m_keptOffset[e.child], kept, ray.maxt)) return true;
        const OctreeNode &node = m_nodes[e.child];
        int order[8];
        float tnear[8];
        int n = sortedChildren(node, slab, ray.mint, ray.maxt, order, tnear);
        for (int k = n - 1; k >= 0; --k) stack[sp++] = {node.child[order[k]], node.count[order[k]], tnear[k]};
    }
    return false;
}

// ---------------------------------------------------------------------------------------------
// seed: the seed report's method, kept for the speed-versus-accuracy chart. Children are
// ordered by the distance from the ray origin to their box and the search stops after the
// first child subtree that reports any hit, which is not always the closest one.

namespace {
float distanceToBox(const OctreeNode &node, int c, const Ray3f &ray) {
    float d2 = 0.0f;
    for (int a = 0; a < 3; ++a) {
        float lo = node.box[a][c], hi = node.box[a][8 + c];
        float d = ray.o[a] < lo ? lo - ray.o[a] : (ray.o[a] > hi ? ray.o[a] - hi : 0.0f);
        d2 += d * d;
    }
    return d2;
}

/// The tree as the seed traversal reads it.
struct SeedTree {
    const std::vector<OctreeNode> &nodes;
    const std::vector<uint32_t> &keptOffset;
    const TriangleStore &store;
};

bool seedRecurse(const SeedTree &tree, uint32_t index, uint32_t count, const Ray3f &ray, const SlabRay &slab,
                 const TriangleRay &tri, Hit &best) {
    // The node's own large triangles count as its first child.
    uint32_t kept = count & OctreeNode::kKeptMask;
    if (kept && tree.store.intersect(tri, tree.keptOffset[index], kept, best)) return true;
    const OctreeNode &node = tree.nodes[index];
    int order[8], n = 0;
    float dist[8];
    for (int c = 0; c < 8; ++c) {
        if (node.box[0][c] > node.box[0][8 + c]) continue;  // empty child
        float d = distanceToBox(node, c, ray);
        int k = n++;
        for (; k > 0 && dist[k - 1] > d; --k) {
            dist[k] = dist[k - 1];
            order[k] = order[k - 1];
        }
        dist[k] = d;
        order[k] = c;
    }
    for (int k = 0; k < n; ++k) {
        int c = order[k];
        float t;
        if (!slab.hit(node, c, ray.mint, best.t, t)) continue;
        uint32_t n = node.count[c];
        bool found = !(n & OctreeNode::kInner) ? tree.store.intersect(tri, node.child[c], n, best)
                                               : seedRecurse(tree, node.child[c], n, ray, slab, tri, best);
        if (found) return true;
    }
    return false;
}
} // namespace

bool OctreeAccel::intersectSeed(const Ray3f &ray, Hit &hit) const {
    const SlabRay slab(ray);
    const TriangleRay tri(ray);
    Hit best;
    best.t = ray.maxt;
    if (!seedRecurse(SeedTree{m_nodes, m_keptOffset, m_triangles}, 0, m_rootCount, ray, slab, tri, best)) return false;
    hit = best;
    return true;
}

} // namespace nori
