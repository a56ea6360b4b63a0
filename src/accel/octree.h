/// \file octree.h
/// \brief `<accel type="octree">`: a midpoint-split octree over the triangles of all meshes,
/// with tight child boxes, flat node storage and several traversals.
#pragma once

#include "triangle.h"
#include <functional>
#include <string>
#include <vector>

namespace nori {

/// \brief One inner node: the tight boxes of its eight children (each the union of its
/// triangles' bounds, clipped to the child's cell) and where each child lives. The children's
/// cells come from three successive midpoint bisections of the node's cell (its Pattern).
/// 256 bytes, one 64-byte line per axis plus one for the child references.
struct alignas(64) OctreeNode {
    /// box[axis][c] is the lower bound of child c, box[axis][8 + c] its upper bound, so one
    /// 16-lane load per axis fetches both slabs of all eight children. An empty child has
    /// lower = +inf and upper = -inf: no ray ever enters it.
    float box[3][16];
    /// Leaf child: word offset of its block in the TriangleStore, count[c] = its triangles
    /// (0 < count < kInner). Inner child: index into the node array, count[c] = innerRef(...).
    /// Empty child: count[c] = 0.
    uint32_t child[8];
    uint32_t count[8];

    /// \brief The bisections that make a node's child cells: first along axis[0], then each
    /// half along axis[1], then each quarter along axis[2]. Child slot c lies on the upper side
    /// of bisection l when bit 2 - l of c is set; (0, 1, 2) are the classic octants. Children
    /// visited in the order j ^ o, j = 0..7, where bit 2 - l of o is the sign of the ray's
    /// direction along axis[l], come front to back (Revelles et al. 2000's observation, which
    /// holds for any nesting of midpoint bisections).
    struct Pattern {
        uint8_t axis[3];
        uint32_t code() const { return uint32_t(axis[0]) | uint32_t(axis[1]) << 2 | uint32_t(axis[2]) << 4; }
        static Pattern fromCode(uint32_t code) {
            return {{uint8_t(code & 3u), uint8_t((code >> 2) & 3u), uint8_t((code >> 4) & 3u)}};
        }
    };

    /// A reference to an inner node (in its parent's count, or the root's): kInner, the node's
    /// pattern code in bits 24-29, and the number of large triangles the node keeps itself
    /// (OctreeAccel::m_kept says where they are, in which groups and what boxes they fill).
    /// With kWide, the simd traversals find the node folded into an OctreeWideNode (child is
    /// then its index in OctreeAccel::m_wide; fold()).
    static constexpr uint32_t kInner = 0x80000000u;
    static constexpr uint32_t kWide = 0x40000000u;
    static constexpr int kPatternShift = 24;
    static constexpr uint32_t kKeptMask = (1u << kPatternShift) - 1u;
    static uint32_t innerRef(const Pattern &p, uint32_t kept) { return kInner | p.code() << kPatternShift | kept; }
};
static_assert(sizeof(OctreeNode) == 256, "OctreeNode must be 4 cache lines");

/// \brief A node of the folded tree (OctreeAccel's simd traversals): up to sixteen cells taken
/// from two or more levels of the octree below one node, tested in one 16-lane slab test
/// instead of a chain of 8-child tests (a wide BVH node's idea, Wald et al. 2008, "Getting rid
/// of packets", applied to an octree's cells). The cells are the leaves of the subtree the
/// fold opened, so their boxes are the octree's own child boxes, bit for bit; a node it opened
/// that kept triangles of its own brings each kept group as one more slot (a list of triangles,
/// like a leaf, in the group's box), in front of that node's cells. 640 bytes.
struct alignas(64) OctreeWideNode {
    static constexpr int kSlots = 16;
    /// box[axis][s] is the lower bound of slot s, box[axis][kSlots + s] its upper bound; an unused
    /// slot has lower = +inf, upper = -inf.
    float box[3][2 * kSlots];
    /// As in OctreeNode (inner children may again be wide: kWide).
    uint32_t child[kSlots];
    uint32_t count[kSlots];
    /// order[signs][j]: the slot the traversal's lane j tests for a ray whose direction has
    /// sign bits \p signs (bit a: d[a] < 0): back to front, the nearest in the last lane. Within each
    /// opened node its children come in the octant order (OctreeNode::Pattern), so this is the
    /// same front-to-back order the unfolded tree visits.
    uint8_t order[8][kSlots];
};
static_assert(sizeof(OctreeWideNode) == 640, "OctreeWideNode must be 10 cache lines");

/// \brief One group of an inner node's kept triangles: where they are (word offset in the
/// TriangleStore), how many, and their bounding box, so that a ray that does not enter the
/// box, or enters it only beyond its closest hit so far, skips them. A node keeps its large
/// triangles in spatially separate groups (a ground quad and a light quad far above it: one
/// box around both would be the whole scene, entered by every ray); \p next is the index of
/// its next group in OctreeAccel::m_kept, 0 after the last.
struct OctreeKept {
    float lo[3], hi[3];
    uint32_t offset, count, next;
    /// In a node's first group, when the node has several: its index in OctreeAccel::m_keptSets
    /// (the same groups laid out for one box test); kNoSet otherwise.
    uint32_t set = kNoSet;
    static constexpr uint32_t kNoSet = ~0u;
    /// At most this many groups per node (the traversal's stack holds them beside the children).
    static constexpr int kMaxGroups = 8;
};

/// \brief The kept groups of a node that has several, laid out as an OctreeNode's children are
/// (box[axis][g] the lower bound of group g, box[axis][8 + g] its upper; an unused slot lower
/// +inf, upper -inf), so that the simd traversals test all their boxes in one eight-lane slab
/// test instead of one scalar test per group. 256 bytes.
struct alignas(64) OctreeKeptSet {
    float box[3][16];
    uint32_t offset[8], count[8];
};
static_assert(sizeof(OctreeKeptSet) == 256, "OctreeKeptSet must be 4 cache lines");
static_assert(OctreeKept::kMaxGroups <= 8, "OctreeKeptSet holds eight groups");

/// \brief Octree accelerator. Properties: `buildRule` (sah* | count | seed), `maxDepth`,
/// `leafSize` (a node with fewer triangles is a leaf), `overlap` (bbox | exact*), `traversal`
/// (seed | sorted | simd*), `intersector` (mt | watertight*), `fold` (whether the simd
/// traversals use wide nodes, see fold(); default: where the node test is a vector test, 8 or 16 lanes),
/// `termination` (`sah` only, true*: whether the cost model counts the rays that stop in a
/// nearer child before reaching a farther one), `lookahead` (`sah` only, true*: whether a split
/// that the cost model rejects because of one child's price as a leaf is built anyway and
/// judged by its subtree's cost).
///
/// Build (octree_build.cpp): every cell splits at its midpoint; triangles are classified
/// against the midplanes by their bounding boxes, the separating-axis test only for those that
/// straddle; children are built as parallel TBB tasks. The `sah` rule (default) makes the
/// eight children by three bisections of the longest side (so cells stay near-cubic on flat
/// or long scenes) unless triangles span those planes (a city's walls cross its horizontal
/// planes) and a sampled surface-area estimate prefers bisections that copy fewer of them,
/// keeps triangles that would be copied into many children in the node itself, and makes a
/// leaf where a surface-area cost model says splitting no longer pays (counting, with
/// `termination`, the rays that stop in a nearer child before they reach a farther one, and
/// with `lookahead`, the subtree a crowded child would get instead of its price as a leaf).
/// `count` is the octree of issue 3 (x, y, z octants, leaf below leafSize); `seed` is the seed
/// report's rule (each later sibling counts one level deeper). `sah` skips the levels of a cell
/// whose triangles all lie in one child (the cell shrinks to it without a node, and without
/// using a level of maxDepth). Every rule stops at maxDepth (node levels) and
/// at a budget of references per triangle for any input: 8 for `count` and `seed`, 1.5 for
/// `sah` (past it, straddling triangles go down loose, uncopied). Memory: 256-byte inner
/// nodes plus one word per node; leaves and kept lists live in the TriangleStore (40 bytes per
/// reference plus 24 bytes per box of 8 triangles, of 16 in leaves above 128: see
/// TriangleStore::blockSize).
///
/// Traversal (octree_traversal.cpp): every traversal culls a child whose entry distance lies
/// beyond the closest hit so far and never stops early (except `seed`), so the first-found
/// hit in a leaf may lie outside that leaf's cell without breaking exactness. Leaves test their
/// triangles sixteen at a time, nearest chunk first (TriangleStore). A node's kept triangles
/// are tested only by rays that enter their bounding box: by `simd` right away if the box comes
/// before the node's nearest child, else when the box's turn comes among the waiting children
/// (so that a closer hit found meanwhile culls them); by the any-hit traversal first. A node's
/// several kept groups (large triangles in separate places, or one group per face of the node's
/// box where the kept triangles lie on its shell: a storey's floor and ceiling, tested each
/// where the ray meets it) get one eight-lane box test for all (OctreeKeptSet).
class OctreeAccel : public Accel {
public:
    /// \brief How children are visited.
    enum class Traversal {
        Seed,    ///< children by distance to their box, stop at the first subtree that hits (inexact)
        Sorted,  ///< exact: children sorted by entry t, skip those beyond the closest hit
        Simd,    ///< exact: all eight boxes in one 8-lane slab test (NodeRay), visited in the ray's octant order;
                 ///< with `fold`, on the folded tree (wide nodes where they save node visits)
    };
    /// \brief How the tree is subdivided.
    enum class BuildRule {
        Sah,    ///< near-cubic cells, large triangles kept high, leaf-or-split by a cost model
        Count,  ///< eight children always, leaf below leafSize (the octree of issue 3)
        Seed,   ///< as Count, but child k of a node counts k + 1 levels deeper (the seed's `++ctr`)
    };
    /// \brief Which triangles a child cell receives.
    enum class Overlap {
        BBox,   ///< the triangle's bounding box touches the cell
        Exact,  ///< separating-axis triangle/box test (bounding box first, SAT only for straddlers)
    };

    explicit OctreeAccel(const PropertyList &props);

    bool intersect(const Ray3f &ray, Hit &hit) const override;
    bool occluded(const Ray3f &ray) const override;
    std::vector<AccelStat> statistics() const override;
    std::string toString() const override;

    /// \brief Bytes owned after the build: nodes and precomputed triangle data.
    size_t bytes() const;
    Traversal traversal() const { return m_traversal; }
    BuildRule buildRule() const { return m_buildRule; }

    /// \brief One inner node as the tests inspect it: where it is, the reference that leads to
    /// it (OctreeNode::innerRef: pattern and kept count) and its depth in nodes (root 0).
    struct NodeView {
        uint32_t index, ref;
        int depth;
        const OctreeNode &node;
        const OctreeKept &kept;  ///< its first kept group (ref & OctreeNode::kKeptMask triangles in all)
        const std::vector<OctreeKept> &keptStore;  ///< where kept.next and the later groups point
        const OctreeAccel &accel;
        /// \brief The index of inner child \p c (node.count[c] & kInner) among the nodes: after
        /// fold(), node.child[c] of a child folded into a wide node is the wide node's index.
        uint32_t childNode(int c) const { return accel.nodeIndexOf(node.child[c], node.count[c]); }
        /// \brief The node's kept groups, in the order the traversals test them.
        std::vector<OctreeKept> keptGroups() const {
            std::vector<OctreeKept> groups;
            if (!(ref & OctreeNode::kKeptMask)) return groups;
            for (const OctreeKept *g = &kept;; g = &keptStore[g->next]) {
                groups.push_back(*g);
                if (!g->next) break;
            }
            return groups;
        }
    };
    /// \brief Call \p visit for every inner node, parents before children.
    template <typename Visit> void forEachNode(Visit visit) const {
        if (m_nodes.empty()) return;
        // (A wide reference, kWide, leads to the node its wide node was folded from.)
        auto unfold = [&](uint32_t child, uint32_t ref) { return std::pair{nodeIndexOf(child, ref), ref & ~OctreeNode::kWide}; };
        std::vector<std::pair<std::pair<uint32_t, uint32_t>, int>> stack{{unfold(m_rootChild, m_rootCount), 0}};
        while (!stack.empty()) {
            auto [indexRef, depth] = stack.back();
            auto [index, ref] = indexRef;
            stack.pop_back();
            const OctreeNode &node = m_nodes[index];
            visit(NodeView{index, ref, depth, node, m_kept[index], m_kept, *this});
            for (int c = 0; c < 8; ++c)
                if (node.count[c] & OctreeNode::kInner) stack.push_back({unfold(node.child[c], node.count[c]), depth + 1});
        }
    }

    /// \brief One node as the simd traversals see it after fold(): a wide node (kSlots) or a
    /// plain one (8, an OctreeNode), its slots' children and references, and the node of
    /// m_nodes it stands for (whose kept groups it tests).
    struct FoldedView {
        bool wide;
        uint32_t index;   ///< in m_wide if wide, else in m_nodes
        uint32_t source;  ///< in m_nodes
        uint32_t ref;     ///< the reference that leads to it
        int slots;
        const uint32_t *child, *count;
        const OctreeWideNode *wideNode;  ///< the node itself if wide
    };
    /// \brief The index among the nodes (as in NodeView) of the inner child reached through
    /// (\p child, \p ref): a wide reference leads to the node its wide node stands for.
    uint32_t nodeIndexOf(uint32_t child, uint32_t ref) const {
        return (ref & OctreeNode::kWide) ? m_wideSource[child] : child;
    }
    /// \brief Call \p visit for every node the simd traversals reach, parents before children.
    void forEachFoldedNode(const std::function<void(const FoldedView &)> &visit) const;
    size_t wideNodes() const { return m_wide.size(); }

    /// \brief Deepest allowed level (the root is level 0); clamped to kMaxDepthLimit.
    static constexpr int kMaxDepthLimit = 32;

protected:
    void buildImpl() override;

private:
    // Traversals (octree_traversal.cpp).
    bool intersectSimd(const Ray3f &ray, Hit &hit) const;
    bool occludedSimd(const Ray3f &ray) const;
    bool intersectSorted(const Ray3f &ray, Hit &hit) const;
    bool occludedSorted(const Ray3f &ray) const;
    bool intersectSeed(const Ray3f &ray, Hit &hit) const;
    // Wide nodes for the simd traversals (octree_fold.cpp).
    void fold();
    // m_keptSets from m_kept (octree_layout.cpp).
    void gatherKeptSets();


    // Settings.
    BuildRule m_buildRule;
    int m_maxDepth;
    int m_leafSize;
    Overlap m_overlap;
    Traversal m_traversal;
    Intersector m_intersector;
    bool m_fold;
    bool m_termination;
    bool m_lookahead;

    // Structure: node 0 is the root (always an inner node), referenced as (0, m_rootCount)
    // (before fold()).
    // m_kept holds, per node, its first kept group (where its triangles are in m_triangles,
    // how many, their box), then the nodes' further groups.
    std::vector<OctreeNode> m_nodes;
    std::vector<OctreeKept> m_kept;
    /// The nodes with several kept groups, their groups again for the simd traversals' one box
    /// test (gatherKeptSets(); OctreeKept::set).
    std::vector<OctreeKeptSet> m_keptSets;
    uint32_t m_rootCount = 0;
    TriangleStore m_triangles;

    // fold(): wide nodes for the simd traversals. Plain nodes whose child was folded refer to
    // it with kWide; nodes opened into a wide node stay in m_nodes (the other traversals and
    // forEachNode walk the unfolded tree). m_wideSource: the node each wide node stands for.
    std::vector<OctreeWideNode> m_wide;
    std::vector<uint32_t> m_wideSource;
    uint32_t m_rootChild = 0;  ///< the root: m_nodes[0], or m_wide[m_rootChild] if m_rootCount has kWide

    // Statistics of the last build.
    struct Stats {
        size_t internalNodes = 0, leafNodes = 0, emptyLeaves = 0, refs = 0, keptRefs = 0, keptNodes = 0, keptGroups = 0;
        int maxDepthReached = 0;
        size_t wideNodes = 0, openedNodes = 0;  ///< fold(): wide nodes, and the nodes they replace
    } m_stats;
};

#ifdef NORI_OCTREE_COUNTERS
/// \brief What the simd traversals did, summed over all queries since the last reset (a
/// measuring build only: -DNORI_OCTREE_COUNTERS; single-threaded use).
struct OctreeCounters {
    uint64_t nodes = 0, keptTris = 0, leaves = 0, leafTris = 0;
    uint64_t wideNodes = 0;  ///< of nodes, the folded tree's wide ones
    uint64_t chunks = 0, exactT = 0;  ///< triangle spans tested (up to 16: a small list, a block or a pair of blocks), t recomputed in double (lanes)
    /// Kernel steps (L lanes each), those with a lane past the edge test (inside the triangle:
    /// the division and the t checks follow), and those with a lane hit in range.
    uint64_t steps = 0, stepsInside = 0, stepsHit = 0;
    uint64_t keptLists = 0, keptChunks = 0;  ///< kept lists tested, and their chunks
    /// Leaves tested and their chunks, by leaf size: up to 16, 32, 64, 128, 256 triangles, more.
    uint64_t leavesBySize[6] = {}, chunksBySize[6] = {};
    /// Kept lists tested and their chunks, by size: up to 4, 16, 64, 256 triangles, more.
    uint64_t keptBySize[5] = {}, keptChunksBySize[5] = {};
    /// If set: visits per inner node (by index), and per visit the children the ray entered
    /// (1..16, 0: none), for per-depth reports.
    std::vector<uint64_t> *nodeVisits = nullptr;
    std::vector<uint64_t> *emptyVisits = nullptr;  ///< if set: per inner node, the visits that entered no child
    uint64_t entered[OctreeWideNode::kSlots + 1] = {};
};
extern OctreeCounters g_octreeCounters;
#endif

/// A measuring build marks a kept list among leaves (waiting on the simd traversal's stack, or
/// a wide node's slot) with this bit in its count, so that it is counted as a kept list; other
/// builds leave counts as they are.
#ifdef NORI_OCTREE_COUNTERS
inline constexpr uint32_t kOctreeKeptTag = 0x40000000u;
#else
inline constexpr uint32_t kOctreeKeptTag = 0;
#endif

} // namespace nori
