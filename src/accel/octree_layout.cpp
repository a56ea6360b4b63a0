/// \file octree_layout.cpp
/// \brief OctreeAccel::buildImpl(): gathers the triangles, runs the subdivision
/// (octree_build.cpp) and lays the temporary tree out as flat nodes (depth-first preorder) and
/// triangle-store blocks, in parallel; then the statistics.
#include "octree_build.h"
#include <tbb/task_group.h>
#include <algorithm>
#include <memory>

namespace nori {

namespace {

using octree_build::TempNode;

/// Subtrees with more references than this are written as parallel tasks.
constexpr size_t kParallelRefs = 4096;

/// Where the flattened tree goes.
struct Layout {
    std::vector<OctreeNode> &nodes;
    std::vector<OctreeKept> &kept;
    TriangleStore &store;
    const std::array<Point3f, 3> *vertices;
};

/// The reference to \p node that its parent stores (count field).
uint32_t innerCount(const TempNode &node) { return OctreeNode::innerRef(node.pattern, uint32_t(node.kept.size())); }

/// Write \p node at \p index (its subtree in preorder after it), its kept groups at word
/// \p offset and its leaves after that; its kept groups beyond the first go to out.kept from
/// \p group on, those of its subtree after them.
void flatten(const TempNode &node, uint32_t index, uint32_t offset, uint32_t group, const Layout &out) {
    OctreeNode &dst = out.nodes[index];
    out.kept[index] = {{Infinity, Infinity, Infinity}, {-Infinity, -Infinity, -Infinity}, offset, 0, 0};
    size_t first = 0;
    for (size_t g = 0; g < node.keptGroups.size(); ++g) {
        const TempNode::KeptGroup &kg = node.keptGroups[g];
        const uint32_t slot = g == 0 ? index : group++;
        OctreeKept &k = out.kept[slot];
        k = {{kg.box.min.x(), kg.box.min.y(), kg.box.min.z()},
             {kg.box.max.x(), kg.box.max.y(), kg.box.max.z()},
             offset,
             kg.count,
             g + 1 < node.keptGroups.size() ? group : 0u,
             OctreeKept::kNoSet};
        out.store.setLeaf(offset, node.kept.data() + first, kg.count, out.vertices, &kg.box);  // (hits outside: other cells)
        offset += uint32_t(TriangleStore::leafWords(kg.count));
        first += kg.count;
    }
    uint32_t next = index + 1;
    // Subtrees large enough to pay for a task are written in parallel (a task_group only
    // where there are some: creating one per node would cost more than small subtrees).
    std::unique_ptr<tbb::task_group> tasks;
    for (int c = 0; c < 8; ++c) {
        const BoundingBox3f &b = node.box[c];
        bool empty = !node.inner[c] && node.refs[c].empty();
        for (int a = 0; a < 3; ++a) {
            dst.box[a][c] = empty ? Infinity : b.min[a];
            dst.box[a][8 + c] = empty ? -Infinity : b.max[a];
        }
        dst.child[c] = 0;
        dst.count[c] = 0;
        if (node.inner[c]) {
            const TempNode &sub = *node.inner[c];
            dst.child[c] = next;
            dst.count[c] = innerCount(sub);
            if (sub.subtreeRefs > kParallelRefs) {
                if (!tasks) tasks = std::make_unique<tbb::task_group>();
                tasks->run([&, next, offset, group] { flatten(sub, next, offset, group, out); });
            } else {
                flatten(sub, next, offset, group, out);
            }
            next += uint32_t(sub.subtreeNodes);
            offset += uint32_t(sub.subtreeWords);
            group += uint32_t(sub.subtreeGroups);
        } else if (!empty) {
            uint32_t count = uint32_t(node.refs[c].size());
            dst.child[c] = offset;
            dst.count[c] = count;
            out.store.setLeaf(offset, node.refs[c].data(), count, out.vertices, &b);
            offset += uint32_t(TriangleStore::leafWords(count));
        }
    }
    if (tasks) tasks->wait();
}

} // namespace

void OctreeAccel::buildImpl() {
    m_nodes.clear();
    m_kept.clear();
    m_rootCount = 0;
    m_stats = Stats();
    const uint32_t total = triangleCount();

    // Gather corners and bounds of every triangle; triangles that no ray can hit (a corner
    // not finite, or all three on one line: triangleCanBeHit) are left out. (The corners are
    // appended: no pass that zeroes them first; the references are plain data, not
    // initialised either.)
    // (The large arrays on huge pages: see allocateLarge().)
    std::vector<std::array<Point3f, 3>, HugePageAllocator<std::array<Point3f, 3>>> vertices;
    vertices.reserve(total);
    // twice each triangle's area, for the `sah` rule
    std::vector<float, HugePageAllocator<float>> areas(total, 0.0f);
    LargeArray<octree_build::Ref> refs = makeLargeArray<octree_build::Ref>(total);
    size_t count = 0;
    BoundingBox3f sceneBox;
    for (size_t m = 0; m < m_meshes.size(); ++m) {
        const Mesh *mesh = m_meshes[m];
        const Point3f *positions = mesh->positions().data();
        const std::array<uint32_t, 3> *faces = mesh->faces().data();
        for (uint32_t f = 0; f < mesh->triangleCount(); ++f) {
            const uint32_t prim = m_offsets[m] + f;  // == vertices.size()
            const std::array<Point3f, 3> v{positions[faces[f][0]], positions[faces[f][1]], positions[faces[f][2]]};
            vertices.push_back(v);
            if (!triangleCanBeHit(v)) continue;
            BoundingBox3f bounds;
            for (int k = 0; k < 3; ++k) bounds.expandBy(v[k]);
            areas[prim] = (v[1] - v[0]).cross(v[2] - v[0]).norm();
            sceneBox.expandBy(bounds);
            refs[count++] = {{bounds.min.x(), bounds.min.y(), bounds.min.z()},
                             {bounds.max.x(), bounds.max.y(), bounds.max.z()}, prim};
        }
    }

    // Root cell: the scene box, each side at least 2^-10 of the longest, so that a flat scene
    // does not put every triangle on every midplane of a zero-thickness cell.
    BoundingBox3f cell = sceneBox;
    if (cell.isValid()) {
        float minSide = cell.extents().maxCoeff() * 0x1p-10f;
        for (int a = 0; a < 3; ++a) {
            float grow = std::max(0.0f, 0.5f * (minSide - cell.extents()[a]));
            cell.min[a] -= grow;
            cell.max[a] += grow;
        }
    }

    octree_build::Input in{vertices.data(), areas.data(), m_buildRule, m_maxDepth, size_t(m_leafSize), m_overlap == Overlap::Exact,
                           m_termination, m_lookahead};
    std::unique_ptr<TempNode> root = octree_build::subdivide(in, cell, sceneBox, refs.get(), count);
    bool rootIsLeaf = !root;
    if (rootIsLeaf) {
        // The root node then holds a single leaf child with every triangle (in their order;
        // subdivide() may have marked some loose).
        root = std::make_unique<TempNode>();
        if (count) root->box[0] = sceneBox;
        root->subtreeRefs = count;
        root->subtreeWords = count ? TriangleStore::leafWords(uint32_t(count)) : 0;
        root->leafIds = makeLargeArray<uint32_t>(count);
        for (size_t i = 0; i < count; ++i) root->leafIds[i] = refs[i].id & ~octree_build::kLooseBit;
        root->refs[0] = {root->leafIds.get(), count};
    }
    refs.reset();
    decltype(areas)().swap(areas);

    if (root->subtreeWords >= size_t(UINT32_MAX))
        throw NoriException("octree: the scene needs {} triangle references, too many for 32-bit offsets",
                            root->subtreeRefs);
    m_nodes.resize(root->subtreeNodes);
    m_nodes.shrink_to_fit();
    m_kept.resize(root->subtreeNodes + root->subtreeGroups);
    m_kept.shrink_to_fit();
    m_rootCount = innerCount(*root);
    m_triangles.reset(m_intersector, root->subtreeWords);
    flatten(*root, 0, 0, uint32_t(root->subtreeNodes), Layout{m_nodes, m_kept, m_triangles, vertices.data()});

    gatherKeptSets();

    // Statistics over the temporary tree (serial; a few ten thousand nodes).
    m_stats.refs = root->subtreeRefs;
    if (rootIsLeaf) {
        m_stats.leafNodes = 1;
        m_stats.emptyLeaves = root->subtreeRefs == 0;
        fold();
        return;
    }
    std::vector<const TempNode *> stack{root.get()};
    while (!stack.empty()) {
        const TempNode *node = stack.back();
        stack.pop_back();
        ++m_stats.internalNodes;
        m_stats.keptRefs += node->kept.size();
        m_stats.keptNodes += !node->kept.empty();
        m_stats.keptGroups += node->keptGroups.size();
        for (int c = 0; c < 8; ++c) {
            m_stats.maxDepthReached = std::max(m_stats.maxDepthReached, node->childDepth[c]);
            if (node->inner[c]) {
                stack.push_back(node->inner[c].get());
                continue;
            }
            ++m_stats.leafNodes;
            if (node->refs[c].empty()) ++m_stats.emptyLeaves;
        }
    }
    fold();
}

void OctreeAccel::gatherKeptSets() {
    m_keptSets.clear();
    size_t sets = 0;
    for (size_t i = 0; i < m_nodes.size(); ++i) sets += m_kept[i].count && m_kept[i].next;
    m_keptSets.reserve(sets);
    for (size_t i = 0; i < m_nodes.size(); ++i) {
        OctreeKept &first = m_kept[i];
        first.set = OctreeKept::kNoSet;
        if (!first.count || !first.next) continue;
        OctreeKeptSet set;
        for (int g = 0; g < 8; ++g) {
            for (int a = 0; a < 3; ++a) {
                set.box[a][g] = Infinity;
                set.box[a][8 + g] = -Infinity;
            }
            set.offset[g] = set.count[g] = 0;
        }
        int g = 0;
        for (uint32_t k = uint32_t(i);; k = m_kept[k].next, ++g) {
            for (int a = 0; a < 3; ++a) {
                set.box[a][g] = m_kept[k].lo[a];
                set.box[a][8 + g] = m_kept[k].hi[a];
            }
            set.offset[g] = m_kept[k].offset;
            set.count[g] = m_kept[k].count;
            if (!m_kept[k].next) break;
        }
        first.set = uint32_t(m_keptSets.size());
        m_keptSets.push_back(set);
    }
}

} // namespace nori
