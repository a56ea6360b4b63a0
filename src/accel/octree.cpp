/// \file octree.cpp
/// \brief Octree accelerator: properties, dispatch and statistics.
#include "octree.h"
#include "lanes.h"

namespace nori {

namespace {
OctreeAccel::Traversal parseTraversal(const PropertyList &props) {
    std::string name = props.getString("traversal", "simd");
    if (name == "seed") return OctreeAccel::Traversal::Seed;
    if (name == "sorted") return OctreeAccel::Traversal::Sorted;
    if (name == "simd") return OctreeAccel::Traversal::Simd;
    props.fail("traversal", fmt::format("unknown traversal '{}' (allowed: seed, sorted, simd)", name));
}

OctreeAccel::Overlap parseOverlap(const PropertyList &props) {
    std::string name = props.getString("overlap", "exact");
    if (name == "bbox") return OctreeAccel::Overlap::BBox;
    if (name == "exact") return OctreeAccel::Overlap::Exact;
    props.fail("overlap", fmt::format("unknown overlap test '{}' (allowed: bbox, exact)", name));
}

OctreeAccel::BuildRule parseBuildRule(const PropertyList &props) {
    std::string name = props.getString("buildRule", "sah");
    if (name == "sah") return OctreeAccel::BuildRule::Sah;
    if (name == "count") return OctreeAccel::BuildRule::Count;
    if (name == "seed") return OctreeAccel::BuildRule::Seed;
    props.fail("buildRule", fmt::format("unknown build rule '{}' (allowed: sah, count, seed)", name));
}

const char *buildRuleName(OctreeAccel::BuildRule r) {
    switch (r) {
    case OctreeAccel::BuildRule::Count: return "count";
    case OctreeAccel::BuildRule::Seed: return "seed";
    default: return "sah";
    }
}

const char *traversalName(OctreeAccel::Traversal t) {
    switch (t) {
    case OctreeAccel::Traversal::Seed: return "seed";
    case OctreeAccel::Traversal::Sorted: return "sorted";
    default: return "simd";
    }
}
} // namespace

OctreeAccel::OctreeAccel(const PropertyList &props) {
    m_buildRule = parseBuildRule(props);
    // `sah`: the cost model decides where to stop; maxDepth only bounds the tree's node levels
    // (levels of empty space above a small object on a huge ground make no node and do not
    // count), and leafSize 17 spares the cost model the nodes of one chunk: such a leaf costs one chunk test (Cost::kChunk), and its
    // split pays only where the children's boxes add up to less than half the node's box
    // (kNode + kChunk * sum P(c) < kChunk). With leafSize 8 the 120k city classified 7,020
    // nodes of 8-16 triangles (68k references) to split 702 of them: 7 % of its build, with
    // no difference in the rays' speed (nori-raytime, city/sphere/room/grass). `count` keeps issue 3's measured defaults (16, 512: leaves of
    // 16-triangle chunks with their own boxes are cheap to test). `seed` has no defaults of
    // its own in the seed report beyond its depth rule; it uses count's.
    const bool sah = m_buildRule == BuildRule::Sah;
    m_maxDepth = props.getInteger("maxDepth", sah ? 24 : 16);
    if (m_maxDepth < 0 || m_maxDepth > kMaxDepthLimit)
        props.fail("maxDepth", fmt::format("maxDepth must be in [0, {}], got {}", kMaxDepthLimit, m_maxDepth));
    m_leafSize = props.getInteger("leafSize", sah ? 17 : 512);
    if (m_leafSize < 1) props.fail("leafSize", fmt::format("leafSize must be at least 1, got {}", m_leafSize));
    m_overlap = parseOverlap(props);
    m_traversal = parseTraversal(props);
    m_intersector = parseIntersector(props, "watertight");
    // Wide nodes pay where the node test is a vector test: on AVX-512 (one instruction for
    // the sixteen boxes) 0.89-0.97x the unfolded tree's ray time on the shapes that fold; on
    // AVX2 (two eight-lane blocks) 0.86-0.97x on tabletop, clutter, room, stadium, turned
    // heightfield, with one loss (sparse shadow rays, 1.09-1.12x; bench/README.md, rounds 8
    // and 31). On one lane the cells are a loop either way. Tests turn it on at every width.
    m_fold = props.getBoolean("fold", lanes::kMaxLanes >= 8);
    // Off: the plain surface-area cost, for comparison (bench/README.md, twelfth round).
    m_termination = props.getBoolean("termination", true);
    // Off: the greedy leaf-or-split rule alone (bench/README.md, twenty-second round).
    m_lookahead = props.getBoolean("lookahead", true);
}

bool OctreeAccel::intersect(const Ray3f &ray, Hit &hit) const {
    if (m_nodes.empty()) return false;  // not built
    switch (m_traversal) {
    case Traversal::Seed: return intersectSeed(ray, hit);
    case Traversal::Sorted: return intersectSorted(ray, hit);
    default: return intersectSimd(ray, hit);
    }
}

bool OctreeAccel::occluded(const Ray3f &ray) const {
    // Any hit: the visiting order only changes speed, so seed and sorted share one traversal.
    if (m_nodes.empty()) return false;
    return m_traversal == Traversal::Simd ? occludedSimd(ray) : occludedSorted(ray);
}

size_t OctreeAccel::bytes() const {
    return m_nodes.capacity() * sizeof(OctreeNode) + m_kept.capacity() * sizeof(OctreeKept) +
           m_keptSets.capacity() * sizeof(OctreeKeptSet) + m_triangles.bytes() +
           m_wide.capacity() * (sizeof(OctreeWideNode) + sizeof(uint32_t));
}

std::vector<AccelStat> OctreeAccel::statistics() const {
    std::vector<AccelStat> stats = Accel::statistics();
    size_t filled = m_stats.leafNodes - m_stats.emptyLeaves;
    // Per non-empty leaf: the references in leaves (kept lists are not leaves).
    stats.push_back({"internal_nodes", double(m_stats.internalNodes), true});
    stats.push_back({"leaf_nodes", double(m_stats.leafNodes), true});
    stats.push_back({"empty_leaves", double(m_stats.emptyLeaves), true});
    stats.push_back({"avg_tris_per_leaf", filled ? double(m_stats.refs - m_stats.keptRefs) / double(filled) : 0.0, false});
    stats.push_back({"max_depth_reached", double(m_stats.maxDepthReached), true});
    stats.push_back({"triangle_refs", double(m_stats.refs), true});
    stats.push_back({"kept_refs", double(m_stats.keptRefs), true});
    stats.push_back({"kept_nodes", double(m_stats.keptNodes), true});
    stats.push_back({"kept_groups", double(m_stats.keptGroups), true});
    stats.push_back({"kept_sets", double(m_keptSets.size()), true});
    stats.push_back({"wide_nodes", double(m_stats.wideNodes), true});
    stats.push_back({"opened_nodes", double(m_stats.openedNodes), true});
    stats.push_back({"bytes", double(bytes()), true});
    return stats;
}

std::string OctreeAccel::toString() const {
    return fmt::format(
        "OctreeAccel[buildRule={}, maxDepth={}, leafSize={}, overlap={}, traversal={}, fold={}, intersector={}, termination={}, lookahead={}]",
        buildRuleName(m_buildRule), m_maxDepth, m_leafSize, m_overlap == Overlap::Exact ? "exact" : "bbox",
        traversalName(m_traversal), m_fold, intersectorName(m_intersector), m_termination, m_lookahead);
}

NORI_REGISTER_CLASS(OctreeAccel, "octree", EAccel);

} // namespace nori
