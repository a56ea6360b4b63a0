/// \file test_octree_fold.cpp
/// \brief The folded tree of the simd traversals (OctreeAccel::fold): it must reach every leaf
/// and kept group of the octree exactly once (an opened node's groups as slots of its wide node), its wide nodes' orders must be permutations of
/// their slots that list the cells in the unfolded tree's front-to-back order, and its answers must be the unfolded tree's bit for
/// bit (same cells, same leaves, same culling: only the number of node tests changes).
#include <gtest/gtest.h>
#include "accel/octree.h"
#include "robust_util.h"
#include <ray_sets.h>
#include <scene_generator.h>
#include <algorithm>
#include <functional>
#include <map>

using namespace nori;

namespace {

std::unique_ptr<Accel> buildOctree(const Mesh &mesh, bool fold) {
    PropertyList p;
    p.setBoolean("fold", fold);
    return robust::makeAccel("octree", p, {&mesh});
}

const OctreeAccel &asOctree(const Accel &accel) { return dynamic_cast<const OctreeAccel &>(accel); }

/// Shapes whose trees differ in kind: filled surfaces (sphere), a ground with kept triangles
/// and many small cells (tabletop), boxes on a plane (city), thin triangles (grass).
const char *const kShapes[] = {"sphere", "tabletop", "city", "grass", "clutter"};

gen::GeneratedScene smallScene(const char *shape) {
    gen::GenParams params;
    params.triangles = std::max<uint64_t>(gen::findShape(shape)->minTriangles, 20000);
    params.seed = 7;
    return gen::generateScene(shape, params);
}

/// Leaves and kept groups (each named by its triangle list: offset, count) reachable through a tree.
struct Reached {
    std::map<std::pair<uint32_t, uint32_t>, int> leaves, kept;
    size_t nodes = 0;
};

using ListName = std::pair<uint32_t, uint32_t>;  ///< a triangle list: offset, count

/// Every node's kept groups (index among the nodes -> its groups in their chain's order).
std::map<uint32_t, std::vector<ListName>> keptByNode(const OctreeAccel &octree) {
    std::map<uint32_t, std::vector<ListName>> byNode;
    octree.forEachNode([&](const OctreeAccel::NodeView &v) {
        for (const OctreeKept &g : v.keptGroups()) byNode[v.index].push_back({g.offset, g.count});
    });
    return byNode;
}

std::vector<ListName> keptGroupsOf(const std::map<uint32_t, std::vector<ListName>> &byNode, uint32_t index) {
    auto it = byNode.find(index);
    return it == byNode.end() ? std::vector<ListName>{} : it->second;
}

Reached reachedUnfolded(const OctreeAccel &octree) {
    Reached r;
    octree.forEachNode([&](const OctreeAccel::NodeView &v) {
        ++r.nodes;
        for (const OctreeKept &g : v.keptGroups()) ++r.kept[{g.offset, g.count}];
        for (int c = 0; c < 8; ++c)
            if (v.node.count[c] && !(v.node.count[c] & OctreeNode::kInner)) ++r.leaves[{v.node.child[c], v.node.count[c]}];
    });
    return r;
}

/// The same through the folded tree: a wide node's own kept groups, and the groups of the nodes
/// it opened, which became slots (told from leaves by \p keptLists, the unfolded tree's groups).
Reached reachedFolded(const OctreeAccel &octree, const Reached &unfolded) {
    const auto byNode = keptByNode(octree);
    Reached r;
    octree.forEachFoldedNode([&](const OctreeAccel::FoldedView &v) {
        ++r.nodes;
        for (const auto &g : keptGroupsOf(byNode, v.source)) ++r.kept[g];
        for (int s = 0; s < v.slots; ++s) {
            if (!v.count[s] || (v.count[s] & OctreeNode::kInner)) continue;
            const ListName list{v.child[s], v.count[s]};
            ++(unfolded.kept.count(list) ? r.kept : r.leaves)[list];
        }
    });
    return r;
}

} // namespace

TEST(OctreeFold, ReachesEveryLeafAndKeptListOnce) {
    size_t foldedShapes = 0, keptSlots = 0;
    for (const char *shape : kShapes) {
        gen::GeneratedScene g = smallScene(shape);
        Mesh mesh(std::move(g.mesh), shape);
        auto accel = buildOctree(mesh, true);
        const OctreeAccel &octree = asOctree(*accel);
        const Reached unfolded = reachedUnfolded(octree), folded = reachedFolded(octree, unfolded);
        EXPECT_EQ(folded.leaves, unfolded.leaves) << shape;
        EXPECT_EQ(folded.kept, unfolded.kept) << shape;
        for (const auto &[leaf, times] : folded.leaves) EXPECT_EQ(times, 1) << shape;
        for (const auto &[group, times] : folded.kept) EXPECT_EQ(times, 1) << shape;
        keptSlots += folded.kept.size() - [&] {
            size_t own = 0;  // the groups wide and plain nodes test themselves
            const auto byNode = keptByNode(octree);
            octree.forEachFoldedNode([&](const OctreeAccel::FoldedView &v) { own += keptGroupsOf(byNode, v.source).size(); });
            return own;
        }();
        if (octree.wideNodes()) {
            ++foldedShapes;
            EXPECT_LT(folded.nodes, unfolded.nodes) << shape;
        }
        // The statistics count what was folded.
        std::map<std::string, double> s;
        for (const AccelStat &st : accel->statistics()) s[st.name] = st.value;
        EXPECT_EQ(s["wide_nodes"], double(octree.wideNodes())) << shape;
        EXPECT_EQ(double(unfolded.nodes - folded.nodes), s["opened_nodes"]) << shape;
    }
    // Not every tree has cells worth folding (thin grass blades fill few of a node's cells),
    // but most of these do: else the checks above would prove nothing.
    EXPECT_GE(foldedShapes, 3u);
    EXPECT_GT(keptSlots, 0u) << "no opened node had kept groups: their slots went untested";
}

TEST(OctreeFold, WideOrdersArePermutations) {
    gen::GeneratedScene g = smallScene("sphere");
    Mesh mesh(std::move(g.mesh), "sphere");
    auto accel = buildOctree(mesh, true);
    size_t wide = 0;
    asOctree(*accel).forEachFoldedNode([&](const OctreeAccel::FoldedView &v) {
        if (!v.wide) return;
        ++wide;
        const OctreeWideNode &n = *v.wideNode;
        for (int signs = 0; signs < 8; ++signs) {
            std::vector<int> seen(OctreeWideNode::kSlots, 0);
            for (int j = 0; j < OctreeWideNode::kSlots; ++j) ++seen[n.order[signs][j]];
            for (int s = 0; s < OctreeWideNode::kSlots; ++s) ASSERT_EQ(seen[s], 1) << "slot " << s << " signs " << signs;
            // Used slots come after the unused ones (lane 0 is the farthest; the nearest cell
            // is the highest lane the ray enters).
            bool usedSeen = false;
            for (int j = 0; j < OctreeWideNode::kSlots; ++j) {
                const int slot = n.order[signs][j];
                const bool used = n.count[slot] != 0;
                if (usedSeen) {
                    ASSERT_TRUE(used) << "an unused slot after a used one";
                }
                usedSeen |= used;
                // An unused slot is never entered.
                if (!used) {
                    ASSERT_GT(n.box[0][slot], n.box[0][OctreeWideNode::kSlots + slot]);
                }
            }
        }
    });
    EXPECT_GT(wide, 0u);
}

TEST(OctreeFold, AnswersAreTheUnfoldedTreesBitForBit) {
    for (const char *shape : kShapes) {
        gen::GeneratedScene g = smallScene(shape);
        std::unique_ptr<Camera> camera = gen::makeCamera(g.camera);
        Mesh mesh(std::move(g.mesh), shape);
        auto folded = buildOctree(mesh, true), unfolded = buildOctree(mesh, false);
        ASSERT_EQ(asOctree(*unfolded).wideNodes(), 0u);
        std::vector<Ray3f> rays = cameraRays(*camera, 1, 3);
        if (rays.size() > 60000) rays.resize(60000);
        const std::vector<Ray3f> box = randomBoxRays(mesh.bbox(), 20000, 5);
        rays.insert(rays.end(), box.begin(), box.end());
        size_t differ = 0, hits = 0;
        for (const Ray3f &ray : rays) {
            Hit a, b;
            const bool fa = folded->intersect(ray, a), fb = unfolded->intersect(ray, b);
            hits += fa;
            const bool same = fa == fb && (!fa || (a.prim == b.prim && a.t == b.t && a.u == b.u && a.v == b.v)) &&
                              folded->occluded(ray) == unfolded->occluded(ray);
            differ += !same;
        }
        EXPECT_EQ(differ, 0u) << shape << " (" << rays.size() << " rays)";
        EXPECT_GT(hits, rays.size() / 10) << shape;
    }
}

// For every wide node and direction-sign combination, the order table lists the cells as the
// unfolded traversal meets them: walking the opened nodes below the wide node's own node,
// children in the octant order (OctreeNode::Pattern), front to back. (The order only affects
// speed; a wrong one would cull less without changing an answer, so only this test sees it.)
TEST(OctreeFold, WideOrdersAreTheUnfoldedFrontToBackOrder) {
    size_t checked = 0;
    for (const char *shape : {"sphere", "clutter", "tabletop"}) {
        gen::GeneratedScene g = smallScene(shape);
        Mesh mesh(std::move(g.mesh), shape);
        auto accel = buildOctree(mesh, true);
        const OctreeAccel &octree = asOctree(*accel);
        std::map<uint32_t, std::pair<const OctreeNode *, uint32_t>> nodes;  // index -> node, its reference
        const auto byNode = keptByNode(octree);
        octree.forEachNode([&](const OctreeAccel::NodeView &v) { nodes[v.index] = {&v.node, v.ref}; });
        octree.forEachFoldedNode([&](const OctreeAccel::FoldedView &v) {
            if (!v.wide) return;
            // A cell is named by its leaf (offset, count) or its node's index.
            auto cellName = [&](uint32_t child, uint32_t count) -> std::pair<uint64_t, uint32_t> {
                if (count & OctreeNode::kInner) return {uint64_t(1) << 32 | octree.nodeIndexOf(child, count), 0};
                return {child, count};
            };
            std::map<std::pair<uint64_t, uint32_t>, int> slotOf;
            for (int s = 0; s < OctreeWideNode::kSlots; ++s)
                if (v.count[s]) slotOf[cellName(v.child[s], v.count[s])] = s;
            for (unsigned signs = 0; signs < 8; ++signs) {
                std::vector<int> expected;  // front to back
                std::function<void(uint32_t)> walk = [&](uint32_t index) {
                    const auto [node, ref] = nodes.at(index);
                    const OctreeNode::Pattern p = OctreeNode::Pattern::fromCode((ref >> OctreeNode::kPatternShift) & 63u);
                    uint32_t octant = 0;
                    for (int l = 0; l < 3; ++l) octant |= ((signs >> p.axis[l]) & 1u) << (2 - l);
                    // An opened node's kept groups come before its cells (the wide node's own stay its own).
                    if (index != v.source)
                        for (const auto &g : keptGroupsOf(byNode, index)) {
                            if (slotOf.count(g)) expected.push_back(slotOf.at(g));
                            else ADD_FAILURE() << shape << ": a kept group of an opened node is no slot of its wide node";
                        }
                    for (uint32_t j = 0; j < 8; ++j) {
                        const uint32_t c = j ^ octant;
                        if (!node->count[c]) continue;
                        const auto name = cellName(node->child[c], node->count[c]);
                        if (slotOf.count(name)) expected.push_back(slotOf.at(name));
                        else if (node->count[c] & OctreeNode::kInner) walk(octree.nodeIndexOf(node->child[c], node->count[c]));
                        else ADD_FAILURE() << shape << ": a leaf of an opened node is no slot of its wide node";
                    }
                };
                walk(v.source);
                std::vector<int> got;  // the used slots, front to back (the table is back to front)
                for (int j = OctreeWideNode::kSlots - 1; j >= 0; --j)
                    if (v.count[v.wideNode->order[signs][j]]) got.push_back(v.wideNode->order[signs][j]);
                ASSERT_EQ(got, expected) << shape << ": wide node " << v.index << ", signs " << signs;
                ++checked;
            }
        });
    }
    EXPECT_GT(checked, 0u);
}
