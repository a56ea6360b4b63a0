/// \file octree_traversal.cpp
/// \brief Octree traversals: simd (default, exact), sorted (exact), seed (inexact, for comparison).
#include "octree.h"
#include "lanes.h"
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <new>
#include <type_traits>

namespace nori {
#ifdef NORI_OCTREE_COUNTERS
OctreeCounters g_octreeCounters;
#define NORI_OCTREE_COUNT(field, n) (g_octreeCounters.field += (n))
#else
#define NORI_OCTREE_COUNT(field, n) ((void)0)
#endif

namespace {
/// Runs \p test, a test of a kept list (\p kept) or of a leaf of \p n triangles, and in a
/// measuring build counts it with the chunks it tested (leaves by size class).
template <typename Test>
inline bool countedList(bool kept, uint32_t n, Test test) {
#ifdef NORI_OCTREE_COUNTERS
    OctreeCounters &c = g_octreeCounters;
    const uint64_t before = c.chunks;
    const bool result = test();
    const uint64_t chunks = c.chunks - before;
    if (kept) {
        c.keptLists += 1;
        c.keptTris += n;
        c.keptChunks += chunks;
        const int size = n <= 4 ? 0 : n <= 16 ? 1 : n <= 64 ? 2 : n <= 256 ? 3 : 4;
        c.keptBySize[size] += 1;
        c.keptChunksBySize[size] += chunks;
    } else {
        const int size = n <= 16 ? 0 : n <= 32 ? 1 : n <= 64 ? 2 : n <= 128 ? 3 : n <= 256 ? 4 : 5;
        c.leaves += 1;
        c.leafTris += n;
        c.leavesBySize[size] += 1;
        c.chunksBySize[size] += chunks;
    }
    return result;
#else
    (void)kept;
    (void)n;
    return test();
#endif
}
} // namespace

namespace {

/// Child slab distances are widened by this relative amount (entry rounded down, exit up),
/// which covers the rounding of (plane - origin) * (1 / d) (Ize 2013, "Robust BVH Ray
/// Traversal"): a box is never culled for a ray that touches it.
constexpr float kSlabEps = 0x1p-20f;

/// Enough for the deepest tree: at most kSlots - 1 cells (of a wide node) and the node's kept
/// groups wait per level.
constexpr int kStackSize = (OctreeWideNode::kSlots - 1 + OctreeKept::kMaxGroups) * (OctreeAccel::kMaxDepthLimit + 1);
/// Room past the stack top for a full-width compress store.
constexpr int kStackSlack = OctreeWideNode::kSlots;

/// Per-ray data of the scalar child box test.
struct SlabRay {
    float o[3], rcpNear[3], rcpFar[3];
    int neg[3];  ///< 1 where the direction's sign bit is set: the entry plane is the box's upper bound
    unsigned signs;  ///< bit a = neg[a]
    /// Byte offsets in an OctreeKept of its entry and exit bounds on axis a: one indexed load
    /// each, where selecting between lo and hi on neg[a] compiled to branches on the ray's
    /// signs (mispredicted on incoherent rays: bench/README.md, thirty-eighth round).
    uint32_t keptEntry[3], keptExit[3];

    explicit SlabRay(const Ray3f &ray) {
        signs = 0;
        for (int a = 0; a < 3; ++a) {
            o[a] = ray.o[a];
            neg[a] = std::signbit(ray.d[a]) ? 1 : 0;
            rcpNear[a] = ray.dRcp[a] * (1.0f - kSlabEps);
            rcpFar[a] = ray.dRcp[a] * (1.0f + kSlabEps);
            signs |= unsigned(neg[a]) << a;
            const uint32_t lo = uint32_t(offsetof(OctreeKept, lo) + a * sizeof(float));
            const uint32_t hi = uint32_t(offsetof(OctreeKept, hi) + a * sizeof(float));
            keptEntry[a] = neg[a] ? hi : lo;
            keptExit[a] = neg[a] ? lo : hi;
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
    /// The same test against a node's kept box.
    bool hit(const OctreeKept &kept, float mint, float maxt, float &tnear) const {
        float t0 = mint, t1 = maxt;
        const char *bytes = reinterpret_cast<const char *>(&kept);
        for (int a = 0; a < 3; ++a) {
            float lo, hi;
            std::memcpy(&lo, bytes + keptEntry[a], sizeof lo);
            std::memcpy(&hi, bytes + keptExit[a], sizeof hi);
            float tn = (lo - o[a]) * rcpNear[a], tf = (hi - o[a]) * rcpFar[a];
            t0 = tn > t0 ? tn : t0;
            t1 = tf < t1 ? tf : t1;
        }
        tnear = t0;
        return t0 <= t1;
    }
};

const SlabRay::OctantTable SlabRay::kOctants;

/// Of the groups in bit set \p g (not empty), the one entered first, by \p entries (the lowest
/// index among equals).
inline int nearestOf(unsigned g, const float *entries) {
    int k = __builtin_ctz(g);
    for (unsigned m = g & (g - 1); m; m &= m - 1)
        if (entries[__builtin_ctz(m)] < entries[k]) k = __builtin_ctz(m);
    return k;
}
/// Pattern code of an inner-node reference.
inline uint32_t patternOf(uint32_t ref) { return (ref >> OctreeNode::kPatternShift) & 63u; }

struct StackEntry {
    uint32_t child, count;  ///< as in OctreeNode
    float tnear;
};

/// Lanes of the eight-child box test: one child per lane on AVX2 and AVX-512 (whose 16 lanes
/// would hold only eight children), a loop over the children on one lane elsewhere. The
/// sixteen cells of a wide node take all the lanes there are.
constexpr int kNodeLanes = lanes::kMaxLanes >= 8 ? 8 : 1;
constexpr int kWideLanes = lanes::kMaxLanes;

/// Lane j < 8 of the node kernel looks at child (7 - j) ^ octant: the ray's back-to-front order,
/// so that pushed in lane order the nearest child ends up on top of the stack.
alignas(32) constexpr uint32_t kBackToFront[8] = {7, 6, 5, 4, 3, 2, 1, 0};

/// Where the cells of a plain node come in the ray's back-to-front order: (7 - j) ^ octant.
template <int L>
struct OctantOrder {
    uint32_t octant;
    lanes::VUint<L> lanesAt(int j) const { return lanes::VUint<L>::loadu(kBackToFront + j) ^ lanes::VUint<L>(octant); }
    uint32_t slot(int j) const { return (7u - uint32_t(j)) ^ octant; }
};
/// The same for a wide node: its table for the ray's direction signs.
template <int L>
struct TableOrder {
    const uint8_t *order;
    lanes::VUint<L> lanesAt(int j) const { return lanes::VUint<L>::loadBytes(order + j); }
    uint32_t slot(int j) const { return order[j]; }
};

template <int S, typename T, typename U>
inline auto lookupCells(const T *table, U idx) {
    if constexpr (S == 8) return lookup8(table, idx);
    else return lookup16(table, idx);
}

/// The box test of a node's S cells (8: OctreeNode; kSlots: OctreeWideNode), written once over
/// lanes::VFloat<L>. Each lane performs the scalar SlabRay::hit operations in the same order,
/// so every width gives the same cells and entry distances bit for bit.
template <int L, int S>
struct CellRay {
    using F = lanes::VFloat<L>;
    using U = lanes::VUint<L>;
    /// The ray's origin and slab reciprocals: plain nodes (most visits) keep them broadcast, once
    /// per ray; wide nodes broadcast them where they use them (as instruction operands, about
    /// as cheap as registers). Broadcasting them for both widths up front, with the copies the
    /// compiler spilled, cost a ray that misses the whole tree a third of its time (20 ns
    /// against 13), and every ray those 7 ns (bench/README.md, thirteenth round).
    static constexpr bool kHeld = S == 8;
    struct Held {
        F org[3], rcpNear[3], rcpFar[3];
    };
    struct Empty {};
    [[no_unique_address]] std::conditional_t<kHeld, Held, Empty> held;
    const SlabRay &ray;
    uint32_t entryHalf[3];  ///< S * neg[a]: where the entry planes start in node.box[a]
    unsigned signs;

    explicit CellRay(const SlabRay &s) : ray(s), signs(s.signs) {
        for (int a = 0; a < 3; ++a) entryHalf[a] = uint32_t(S) * uint32_t(s.neg[a]);
        if constexpr (kHeld)
            for (int a = 0; a < 3; ++a) {
                held.org[a] = F(s.o[a]);
                held.rcpNear[a] = F(s.rcpNear[a]);
                held.rcpFar[a] = F(s.rcpFar[a]);
            }
    }
    F org(int a) const { if constexpr (kHeld) return held.org[a]; else return F(ray.o[a]); }
    F rcpNear(int a) const { if constexpr (kHeld) return held.rcpNear[a]; else return F(ray.rcpNear[a]); }
    F rcpFar(int a) const { if constexpr (kHeld) return held.rcpFar[a]; else return F(ray.rcpFar[a]); }

    /// The cells (boxes \p box, children and counts as in OctreeNode) that the ray enters within
    /// [mint, maxt], visited back to front in lanes as \p order says: the nearest goes to
    /// \p nearChild and \p nearCount, the others onto the stack, farthest first, with their entry
    /// distances; \p entry holds the entry distances of the last block tested, the nearest
    /// cell's in lane \p nearLane. Returns how many were pushed, or -1 when the ray enters no
    /// cell. Handing the nearest cell over in registers spares the traversal a store and an
    /// immediate reload of the stack top (a store-forwarding stall on the hot path), and its
    /// cull test: it was entered before the closest hit, which cannot have changed since.
    /// Without \p kEntries (an any-hit query, which culls nothing) the one-block test does not
    /// store the waiting cells' entry distances.
    template <bool kEntries, typename Order>
    int push(const float (&box)[3][2 * S], const uint32_t *cellChild, const uint32_t *cellCount, Order order, float mint,
             float maxt, uint32_t *child, uint32_t *count, float *tnear, uint32_t &nearChild, uint32_t &nearCount, F &entry,
             int &nearLane) const {
        // The slabs of L cells from \p first in the node's own order: entry and exit distances.
        // The box loads and the arithmetic on them need only the node's address, not the
        // order (a chain of its own), so the two run side by side.
        auto slabs = [&](int first, F &t0, F &t1) {
            t0 = F(mint);
            t1 = F(maxt);
            for (int a = 0; a < 3; ++a) {
                F tn = (F::loadu(box[a] + entryHalf[a] + first) - org(a)) * rcpNear(a);
                F tf = (F::loadu(box[a] + (S - entryHalf[a]) + first) - org(a)) * rcpFar(a);
                t0 = max(tn, t0);  // the second operand on NaN: a NaN never narrows the interval
                t1 = min(tf, t1);
            }
        };
        if constexpr (L == S) {
            // One block, permuted into the ray's order at the end (lane-wise operations commute
            // with the permutation: the same bits as permuting first).
            F t0, t1;
            slabs(0, t0, t1);
            // The cells entered, in the node's order. One cell (most visits that enter any) is
            // the nearest without the ray's order: no permutation and no order lookup between
            // the box test and the next node's address, the traversal's critical path.
            const unsigned cells = bits(t0 <= t1);
            if (cells == 0) return -1;
            if (!(cells & (cells - 1))) {
                const int only = __builtin_ctz(cells);
                nearChild = cellChild[only];
                nearCount = cellCount[only];
                entry = t0;
                nearLane = only;
                return 0;
            }
            const U c = order.lanesAt(0);
            t0 = permute(t0, c);
            t1 = permute(t1, c);
            // The lanes entered, as bits (edited in a general register, not as a vector mask):
            // the nearest cell is the highest set lane; the others are pushed.
            unsigned hit = bits(t0 <= t1);
            const int top = 31 - __builtin_clz(hit);
            const uint32_t nearest = order.slot(top);
            nearChild = cellChild[nearest];
            nearCount = cellCount[nearest];
            entry = t0;
            nearLane = top;
            hit ^= 1u << top;
            lanes::compressStoreBits(hit, permute(U::loadu(cellChild), c), child);
            if constexpr (kEntries) {
                lanes::compressStoreBits(hit, permute(U::loadu(cellCount), c), count);
                return lanes::compressStoreBits(hit, t0, tnear);
            } else {
                return lanes::compressStoreBits(hit, permute(U::loadu(cellCount), c), count);
            }
        } else {
            // Several blocks: all cells in the node's order first (plain loads, no lookups
            // per box bound), their hits as bits and their entry distances in \p entries; then
            // block by block in the ray's order, each lane looking up its cell's bit and entry.
            [[maybe_unused]] alignas(64) float entries[S];
            uint32_t hitCells = 0;
            for (int first = 0; first < S; first += L) {
                F t0, t1;
                slabs(first, t0, t1);
                hitCells |= bits(t0 <= t1) << first;
                if constexpr (kEntries) t0.storeu(entries + first);
            }
            if (hitCells == 0) return -1;
            if (!(hitCells & (hitCells - 1))) {  // one cell: as above
                const int only = __builtin_ctz(hitCells);
                nearChild = cellChild[only];
                nearCount = cellCount[only];
                if constexpr (kEntries) entry = F(entries[only]);
                nearLane = 0;
                return 0;
            }
            int k = 0, lastBlock = 0;
            unsigned lastHit = 0;  // the entered lanes of the last block with any
            for (int j = 0; j < S; j += L) {
                const U c = order.lanesAt(j);
                const unsigned hit = lanes::bitsAt(hitCells, c);
                if (hit == 0) continue;
                lastBlock = j;
                lastHit = hit;
                lanes::compressStoreBits(hit, lookupCells<S>(cellChild, c), child + k);
                const int pushed = lanes::compressStoreBits(hit, lookupCells<S>(cellCount, c), count + k);
                // (An any-hit query needs no entry distances: neither their lookup nor their store.)
                if constexpr (kEntries)
                    lanes::compressStoreBits(hit, lookupCells<S>(static_cast<const float *>(entries), c), tnear + k);
                k += pushed;
            }
            // The last one pushed is the nearest: handed over from the node itself, not read back
            // from the stack just written (a wait on the stores; sparse shadow rays 0.96-0.98,
            // room 0.97, the rest within ±1.5 %: bench/README.md, thirty-second round).
            const uint32_t nearest = order.slot(lastBlock + 31 - __builtin_clz(lastHit));
            nearChild = cellChild[nearest];
            nearCount = cellCount[nearest];
            if constexpr (kEntries) entry = F(entries[nearest]);
            nearLane = 0;
            return k - 1;
        }
    }

    /// The boxes of a node's kept groups (OctreeKeptSet) that the ray enters within [mint, maxt]:
    /// bit g for group g, its entry distance in \p tnear[g]. The same operations as
    /// SlabRay::hit on each group's box, so the same answers bit for bit.
    unsigned enter(const OctreeKeptSet &set, float mint, float maxt, float *tnear) const {
        static_assert(S == 8);
        unsigned entered = 0;
        for (int first = 0; first < 8; first += L) {
            F t0 = F(mint), t1 = F(maxt);
            for (int a = 0; a < 3; ++a) {
                F tn = (F::loadu(set.box[a] + entryHalf[a] + first) - org(a)) * rcpNear(a);
                F tf = (F::loadu(set.box[a] + (S - entryHalf[a]) + first) - org(a)) * rcpFar(a);
                t0 = max(tn, t0);
                t1 = min(tf, t1);
            }
            entered |= bits(t0 <= t1) << first;
            t0.storeu(tnear + first);
        }
        return entered;
    }

    /// An OctreeNode's children, reached through a reference with pattern \p code.
    template <bool kEntries = true>
    int push(const OctreeNode &node, uint32_t code, float mint, float maxt, uint32_t *child, uint32_t *count,
             float *tnear, uint32_t &nearChild, uint32_t &nearCount, F &entry, int &nearLane) const {
        static_assert(S == 8);
        return push<kEntries>(node.box, node.child, node.count, OctantOrder<L>{SlabRay::kOctants[code][signs]}, mint, maxt,
                              child, count, tnear, nearChild, nearCount, entry, nearLane);
    }
    /// A wide node's cells.
    template <bool kEntries = true>
    int push(const OctreeWideNode &node, float mint, float maxt, uint32_t *child, uint32_t *count, float *tnear,
             uint32_t &nearChild, uint32_t &nearCount, F &entry, int &nearLane) const {
        static_assert(S == OctreeWideNode::kSlots);
        return push<kEntries>(node.box, node.child, node.count, TableOrder<L>{node.order[signs]}, mint, maxt, child, count,
                              tnear, nearChild, nearCount, entry, nearLane);
    }
};
using SimdRay = CellRay<kNodeLanes, 8>;
using WideRay = CellRay<kWideLanes, OctreeWideNode::kSlots>;

/// The kept groups of a node that the ray enters (enteredGroups).
struct KeptEntries {
    uint32_t offset[8], count[8];
    float tnear[8];
};

/// The groups of \p set whose boxes the ray enters within [mint, maxt], into \p out nearest
/// first (so that a hit in one culls those behind it); returns how many. Out of line: most
/// nodes keep one group or none, and the traversal loops run faster without this code in them
/// (it hands its answers back in memory rather than taking the loops' state by reference,
/// which would move that state out of registers).
[[gnu::noinline]] int enteredGroups(const OctreeKeptSet &set, const SimdRay &simd, float mint, float maxt, KeptEntries &out) {
    alignas(32) float entries[8];
    int n = 0;
    for (unsigned g = simd.enter(set, mint, maxt, entries); g; ++n) {
        const int k = nearestOf(g, entries);
        g &= ~(1u << k);
        out.offset[n] = set.offset[k];
        out.count[n] = set.count[k];
        out.tnear[n] = entries[k];
    }
    return n;
}

/// The triangle kernels' per-ray setup (TriangleRay: the watertight shear, three divisions),
/// made when the ray first reaches a triangle. In sparse scenes (a ground plane, a room, a
/// city's streets) most shadow and diffuse rays leave the tree through empty cells and never
/// need it; the cull limit needs only cullAbs, which is cheap.
class LazyTriangleRay {
public:
    explicit LazyTriangleRay(const Ray3f &ray) : m_ray(ray), m_cullAbs(TriangleRay::cullAbsOf(ray)) {}
    float cullLimit(float best) const { return TriangleRay::cullLimitOf(best, m_cullAbs); }
    const TriangleRay &get() {
        if (!m_ready) {
            new (m_storage) TriangleRay(m_ray, m_cullAbs);
            m_ready = true;
        }
        return *std::launder(reinterpret_cast<const TriangleRay *>(m_storage));
    }

private:
    const Ray3f &m_ray;
    float m_cullAbs;
    bool m_ready = false;
    alignas(TriangleRay) unsigned char m_storage[sizeof(TriangleRay)];
};

} // namespace

// ---------------------------------------------------------------------------------------------
// simd: one 8-box test per node (CellRay), children in the ray's octant order, or one 16-box
// test per wide node (fold()), cells in its order table's. For the midpoint split,
// child index XOR the direction's sign bits orders the cells front to back (Revelles et al.
// 2000's observation); the order only affects speed, exactness comes from culling every
// entry beyond the closest hit found so far and never stopping early.

bool OctreeAccel::intersectSimd(const Ray3f &ray, Hit &hit) const {
    const SlabRay slab(ray);
    const SimdRay simd(slab);
    const WideRay wide_(slab);
    LazyTriangleRay tri(ray);
    Hit best;
    best.t = ray.maxt;
    const float mint = ray.mint;  // (read through ray, it was read again on every visit)

    // Structure-of-arrays stack, with room for a full-width store past the top.
    alignas(64) uint32_t stackChild[kStackSize + kStackSlack], stackCount[kStackSize + kStackSlack];
    alignas(64) float stackT[kStackSize + kStackSlack];
    uint32_t child = m_rootChild, count = m_rootCount;
    int sp = 0;
    // Boxes entered beyond this are culled: tri.cullLimit(best.t), updated where best changes
    // (a list test that finds a closer hit) rather than recomputed from best.t, which lives in
    // memory (the list tests update it), on every visit and pop: up to 6 % faster on primary
    // and diffuse rays (bench/README.md, thirty-second round).
    float limit = tri.cullLimit(best.t);
    for (;;) {
        if (count & OctreeNode::kInner) {
            NORI_OCTREE_COUNT(nodes, 1);
            uint32_t nearChild, nearCount;
            // Entry distances, the nearest child's in lane nearLane (read where kept groups need it).
            SimdRay::F entry;
            WideRay::F wideEntry;
            int nearLane = 0;
            const bool wide = count & OctreeNode::kWide;
            int pushed = wide ? wide_.push(m_wide[child], mint, limit, stackChild + sp, stackCount + sp, stackT + sp,
                                           nearChild, nearCount, wideEntry, nearLane)
                              : simd.push(m_nodes[child], patternOf(count), mint, limit, stackChild + sp,
                                          stackCount + sp, stackT + sp, nearChild, nearCount, entry, nearLane);
#ifdef NORI_OCTREE_COUNTERS
            if (g_octreeCounters.nodeVisits) ++(*g_octreeCounters.nodeVisits)[nodeIndexOf(child, count)];
            if (g_octreeCounters.emptyVisits && pushed < 0) ++(*g_octreeCounters.emptyVisits)[nodeIndexOf(child, count)];
            g_octreeCounters.wideNodes += wide;
            ++g_octreeCounters.entered[pushed + 1];
#endif
            // descend: the nearest child is still to be entered; pushed: siblings on the stack.
            bool descend = pushed >= 0;
            pushed = std::max(pushed, 0);
            // The node's own large triangles, group by group, if the ray enters the group's box:
            // now if that box comes before the nearest child, else in order of entry among the
            // waiting children.
            if (count & OctreeNode::kKeptMask) {
                const float tc = !descend ? 0.0f : wide ? lane(wideEntry, nearLane) : lane(entry, nearLane);
                // A group entered at tk: tested now, or waits among the children by entry.
                auto visitGroup = [&](uint32_t offset, uint32_t n, float tk) {
                    if (!descend || tk <= tc) {
                        if (countedList(true, n, [&] { return m_triangles.intersect(tri.get(), offset, n, best); }))
                            limit = tri.cullLimit(best.t);
                        if (descend && tc > limit) descend = false;  // the nearest child now lies beyond the hit
                    } else {
                        int i = sp + pushed;
                        for (; i > sp && stackT[i - 1] < tk; --i) {
                            stackChild[i] = stackChild[i - 1];
                            stackCount[i] = stackCount[i - 1];
                            stackT[i] = stackT[i - 1];
                        }
                        stackChild[i] = offset;
                        stackCount[i] = n | kOctreeKeptTag;  // a leaf entry, tagged for a measuring build's counts
                        stackT[i] = tk;
                        ++pushed;
                    }
                };
                // (A node's first kept group sits at its index among the nodes.)
                const OctreeKept &group = m_kept[nodeIndexOf(child, count)];
                float tk;
                if (group.set == OctreeKept::kNoSet) {  // one group
                    if (slab.hit(group, mint, limit, tk)) visitGroup(group.offset, group.count, tk);
                } else {  // several groups: one box test for all, nearest first
                    KeptEntries e;
                    const int n = enteredGroups(m_keptSets[group.set], simd, mint, limit, e);
                    for (int k = 0; k < n; ++k)
                        if (e.tnear[k] <= limit) visitGroup(e.offset[k], e.count[k], e.tnear[k]);
                }
            }
            sp += pushed;
            if (descend) {  // descend into the nearest child at once
                child = nearChild;
                count = nearCount;
                continue;
            }
        } else {
            if (countedList(count & kOctreeKeptTag, count & ~kOctreeKeptTag,
                            [&] { return m_triangles.intersect(tri.get(), child, count & ~kOctreeKeptTag, best); }))
                limit = tri.cullLimit(best.t);
        }
        // Next: the top of the stack, skipping entries beyond the closest hit so far.
        while (sp > 0 && stackT[sp - 1] > limit) --sp;
        if (sp == 0) break;
        --sp;
        child = stackChild[sp];
        count = stackCount[sp];
    }
    if (best.prim == ~0u) return false;
    hit = best;
    return true;
}

bool OctreeAccel::occludedSimd(const Ray3f &ray) const {
    const SlabRay slab(ray);
    const SimdRay simd(slab);
    const WideRay wide_(slab);
    LazyTriangleRay tri(ray);

    alignas(64) uint32_t stackChild[kStackSize + kStackSlack], stackCount[kStackSize + kStackSlack];
    alignas(64) float stackT[kStackSize + kStackSlack];
    uint32_t child = m_rootChild, count = m_rootCount;
    int sp = 0;
    for (;;) {
        if (count & OctreeNode::kInner) {
            NORI_OCTREE_COUNT(nodes, 1);
            const bool wide = count & OctreeNode::kWide;
#ifdef NORI_OCTREE_COUNTERS
            g_octreeCounters.wideNodes += wide;
#endif
            // The node's own large triangles first (the likeliest occluders), if the ray enters their box.
            // (Group by group, stopping at the first that occludes: the kept sets' one box test
            // for all groups measured slower here.)
            if (count & OctreeNode::kKeptMask)
                for (uint32_t g = nodeIndexOf(child, count);; g = m_kept[g].next) {
                    const OctreeKept &group = m_kept[g];
                    float tk;
                    if (slab.hit(group, ray.mint, ray.maxt, tk) && countedList(true, group.count, [&] {
                            return m_triangles.occluded(tri.get(), group.offset, group.count, ray.maxt);
                        }))
                        return true;
                    if (!group.next) break;
                }
            uint32_t nearChild, nearCount;
            SimdRay::F entry;
            WideRay::F wideEntry;
            int nearLane;
            // (No entry distances: an any-hit query culls nothing.)
            int pushed = wide ? wide_.push<false>(m_wide[child], ray.mint, ray.maxt, stackChild + sp, stackCount + sp,
                                                  stackT + sp, nearChild, nearCount, wideEntry, nearLane)
                              : simd.push<false>(m_nodes[child], patternOf(count), ray.mint, ray.maxt, stackChild + sp,
                                                 stackCount + sp, stackT + sp, nearChild, nearCount, entry, nearLane);
            if (pushed >= 0) {
                sp += pushed;
                child = nearChild;
                count = nearCount;
                continue;
            }
        } else {
            if (countedList(count & kOctreeKeptTag, count & ~kOctreeKeptTag,
                            [&] { return m_triangles.occluded(tri.get(), child, count & ~kOctreeKeptTag, ray.maxt); }))
                return true;
        }
        if (sp == 0) break;
        --sp;
        child = stackChild[sp];
        count = stackCount[sp];
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
        if (e.tnear > tri.cullLimit(best.t)) continue;
        if (!(e.count & OctreeNode::kInner)) {
            m_triangles.intersect(tri, e.child, e.count, best);
            continue;
        }
        if (e.count & OctreeNode::kKeptMask)
            for (uint32_t g = e.child;; g = m_kept[g].next) {
                m_triangles.intersect(tri, m_kept[g].offset, m_kept[g].count, best);
                if (!m_kept[g].next) break;
            }
        const OctreeNode &node = m_nodes[e.child];
        int order[8];
        float tnear[8];
        int n = sortedChildren(node, slab, ray.mint, tri.cullLimit(best.t), order, tnear);
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
        if (e.count & OctreeNode::kKeptMask)
            for (uint32_t g = e.child;; g = m_kept[g].next) {
                if (m_triangles.occluded(tri, m_kept[g].offset, m_kept[g].count, ray.maxt)) return true;
                if (!m_kept[g].next) break;
            }
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
    const std::vector<OctreeKept> &kept;
    const TriangleStore &store;
};

bool seedRecurse(const SeedTree &tree, uint32_t index, uint32_t count, const Ray3f &ray, const SlabRay &slab,
                 const TriangleRay &tri, Hit &best) {
    // The node's own large triangles count as its first child.
    if (count & OctreeNode::kKeptMask) {
        bool found = false;
        for (uint32_t g = index;; g = tree.kept[g].next) {
            found |= tree.store.intersect(tri, tree.kept[g].offset, tree.kept[g].count, best);
            if (!tree.kept[g].next) break;
        }
        if (found) return true;
    }
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
    if (!seedRecurse(SeedTree{m_nodes, m_kept, m_triangles}, 0, m_rootCount, ray, slab, tri, best)) return false;
    hit = best;
    return true;
}

} // namespace nori
