/// \file octree_build.cpp
/// \brief Octree construction: a parallel recursive split into a temporary tree, then a parallel
/// flattening into the node array and the triangle store.
#include "octree.h"
#include "triangle_box.h"
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>
#include <algorithm>
#include <memory>

namespace nori {

namespace {

/// Subtrees with more references than this are built as parallel tasks.
constexpr size_t kParallelRefs = 4096;

/// The leaves of the whole tree hold at most this many references per triangle (see split()).
constexpr double kRefBudget = 8.0;

/// Read-only inputs of the build.
struct BuildInput {
    const std::vector<std::array<Point3f, 3>> &vertices;  ///< corners of every global triangle
    const std::vector<BoundingBox3f> &bounds;              ///< bounding box of every global triangle
    int maxDepth;
    size_t leafSize;
    bool exact;
};

/// An inner node of the temporary tree. A child is an inner node (inner[c] set), a leaf
/// (refs[c] non-empty) or empty.
struct TempNode {
    BoundingBox3f box[8];  ///< tight boxes
    std::unique_ptr<TempNode> inner[8];
    std::vector<uint32_t> refs[8];
    size_t subtreeNodes = 1;  ///< inner nodes in this subtree, this one included
    size_t subtreeRefs = 0;   ///< triangle references in the leaves of this subtree
    size_t subtreeWords = 0;  ///< TriangleStore words of the leaves of this subtree
};

/// Cell of child \p c of \p cell: bit 0/1/2 of c selects the upper half along x/y/z.
BoundingBox3f childCell(const BoundingBox3f &cell, int c) {
    Point3f mid = cell.center();
    BoundingBox3f b;
    for (int a = 0; a < 3; ++a) {
        bool upper = (c >> a) & 1;
        b.min[a] = upper ? mid[a] : cell.min[a];
        b.max[a] = upper ? cell.max[a] : mid[a];
    }
    return b;
}

/// Split \p refs (the triangles touching \p cell, a node at \p depth) into eight children and
/// recurse. Returns null when the split makes no progress; the caller then keeps a leaf.
///
/// Reference budget: the node may hold at most \p budget references in the leaves below it. A
/// split whose children hold more is refused, and each child inherits the share of the budget
/// proportional to its references (at least its own count). The root gets kRefBudget times the
/// triangle count, so no input (needles spanning the box, huge triangles) can make the tree
/// hold more than kRefBudget references per triangle.
std::unique_ptr<TempNode> split(const BuildInput &in, const BoundingBox3f &cell, const std::vector<uint32_t> &refs,
                                int depth, double budget) {
    const size_t n = refs.size();
    const Point3f mid = cell.center();
    BoundingBox3f cells[8];
    for (int c = 0; c < 8; ++c) cells[c] = childCell(cell, c);

    // Candidate children from the bounding box against the three midplanes (closed: a box
    // touching a plane goes to both sides), refined by the SAT only for straddling triangles.
    std::vector<uint8_t> masks(n);
    auto classify = [&](size_t i) {
        const BoundingBox3f &b = in.bounds[refs[i]];
        unsigned mx = (b.min.x() <= mid.x() ? 0x55u : 0u) | (b.max.x() >= mid.x() ? 0xAAu : 0u);
        unsigned my = (b.min.y() <= mid.y() ? 0x33u : 0u) | (b.max.y() >= mid.y() ? 0xCCu : 0u);
        unsigned mz = (b.min.z() <= mid.z() ? 0x0Fu : 0u) | (b.max.z() >= mid.z() ? 0xF0u : 0u);
        unsigned mask = mx & my & mz;
        // Two candidates (one midplane straddled) with the box inside the cell: the triangle is
        // connected, reaches both closed sides of the plane and stays in one column of
        // children, so it touches both; the SAT is needed only otherwise.
        bool inside = (b.min.array() >= cell.min.array()).all() && (b.max.array() <= cell.max.array()).all();
        if (in.exact && (mask & (mask - 1)) && !(inside && __builtin_popcount(mask) == 2)) {
            const auto &v = in.vertices[refs[i]];
            unsigned kept = 0;
            for (unsigned m = mask; m; m &= m - 1) {
                int c = __builtin_ctz(m);
                if (triangleOverlapsBox(v[0], v[1], v[2], cells[c])) kept |= 1u << c;
            }
            if (kept) mask = kept;  // never lose a triangle to rounding
        }
        masks[i] = uint8_t(mask);
    };
    if (n > 8 * kParallelRefs)
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t> &r) {
            for (size_t i = r.begin(); i != r.end(); ++i) classify(i);
        });
    else
        for (size_t i = 0; i < n; ++i) classify(i);

    size_t counts[8] = {};
    for (uint8_t m : masks)
        for (unsigned b = m; b; b &= b - 1) ++counts[__builtin_ctz(b)];
    size_t sum = 0, largest = 0;
    for (size_t c : counts) {
        sum += c;
        largest = std::max(largest, c);
    }
    // No progress: the triangles are mostly larger than the children (each lands in more than
    // half of them), or the fullest child keeps every triangle while many straddle (a vertex
    // fan, stacked identical triangles). Splitting again would only multiply references.
    if (sum > 4 * n || (largest == n && sum >= 2 * n) || double(sum) > budget) return nullptr;

    auto node = std::make_unique<TempNode>();
    for (int c = 0; c < 8; ++c) node->refs[c].reserve(counts[c]);
    for (size_t i = 0; i < n; ++i)
        for (unsigned b = masks[i]; b; b &= b - 1) {
            int c = __builtin_ctz(b);
            node->refs[c].push_back(refs[i]);
            const BoundingBox3f &tb = in.bounds[refs[i]];
            node->box[c].expandBy(BoundingBox3f(tb.min.cwiseMax(cells[c].min), tb.max.cwiseMin(cells[c].max)));
        }
    masks = {};

    auto buildChild = [&](int c) {
        std::vector<uint32_t> &list = node->refs[c];
        if (list.size() < in.leafSize || depth + 1 >= in.maxDepth) return;
        double share = budget * double(list.size()) / double(sum);
        std::unique_ptr<TempNode> sub = split(in, cells[c], list, depth + 1, share);
        if (!sub) return;
        node->inner[c] = std::move(sub);
        std::vector<uint32_t>().swap(list);
    };
    if (n > kParallelRefs) {
        tbb::task_group group;
        for (int c = 0; c < 8; ++c) group.run([&, c] { buildChild(c); });
        group.wait();
    } else {
        for (int c = 0; c < 8; ++c) buildChild(c);
    }
    for (int c = 0; c < 8; ++c) {
        if (node->inner[c]) {
            node->subtreeNodes += node->inner[c]->subtreeNodes;
            node->subtreeRefs += node->inner[c]->subtreeRefs;
            node->subtreeWords += node->inner[c]->subtreeWords;
        } else {
            node->subtreeRefs += node->refs[c].size();
            if (!node->refs[c].empty()) node->subtreeWords += TriangleStore::leafWords(uint32_t(node->refs[c].size()));
        }
    }
    return node;
}

/// Write \p node at \p index (children in DFS preorder after it) and its leaves from word \p offset.
void flatten(const TempNode &node, uint32_t index, uint32_t offset, std::vector<OctreeNode> &nodes,
             TriangleStore &store, const std::vector<std::array<Point3f, 3>> &vertices) {
    OctreeNode &out = nodes[index];
    uint32_t next = index + 1;
    tbb::task_group group;
    bool spawned = false;
    for (int c = 0; c < 8; ++c) {
        const BoundingBox3f &b = node.box[c];
        bool empty = !node.inner[c] && node.refs[c].empty();
        for (int a = 0; a < 3; ++a) {
            out.box[a][c] = empty ? Infinity : b.min[a];
            out.box[a][8 + c] = empty ? -Infinity : b.max[a];
        }
        out.child[c] = 0;
        out.count[c] = 0;
        if (node.inner[c]) {
            const TempNode &sub = *node.inner[c];
            out.child[c] = next;
            if (sub.subtreeRefs > kParallelRefs) {
                spawned = true;
                group.run([&, next, offset] { flatten(sub, next, offset, nodes, store, vertices); });
            } else {
                flatten(sub, next, offset, nodes, store, vertices);
            }
            next += uint32_t(sub.subtreeNodes);
            offset += uint32_t(sub.subtreeWords);
        } else if (!empty) {
            uint32_t count = uint32_t(node.refs[c].size());
            out.child[c] = offset;
            out.count[c] = count;
            store.setLeaf(offset, node.refs[c].data(), count, vertices);
            offset += uint32_t(TriangleStore::leafWords(count));
        }
    }
    if (spawned) group.wait();
}

} // namespace

void OctreeAccel::buildImpl() {
    m_nodes.clear();
    m_stats = Stats();
    const uint32_t total = triangleCount();

    // Gather corners and bounds of every triangle; triangles with a non-finite corner can
    // never be hit meaningfully and are left out.
    std::vector<std::array<Point3f, 3>> vertices(total);
    std::vector<BoundingBox3f> bounds(total);
    std::vector<uint32_t> all;
    all.reserve(total);
    BoundingBox3f sceneBox;
    for (size_t m = 0; m < m_meshes.size(); ++m) {
        const Mesh *mesh = m_meshes[m];
        for (uint32_t f = 0; f < mesh->triangleCount(); ++f) {
            uint32_t prim = m_offsets[m] + f;
            auto &v = vertices[prim];
            for (int k = 0; k < 3; ++k) v[k] = mesh->vertex(f, k);
            if (!(v[0].allFinite() && v[1].allFinite() && v[2].allFinite())) continue;
            for (int k = 0; k < 3; ++k) bounds[prim].expandBy(v[k]);
            sceneBox.expandBy(bounds[prim]);
            all.push_back(prim);
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

    BuildInput in{vertices, bounds, m_maxDepth, size_t(m_leafSize), m_overlap == Overlap::Exact};
    std::unique_ptr<TempNode> root;
    if (all.size() >= size_t(m_leafSize) && m_maxDepth > 0) root = split(in, cell, all, 0, kRefBudget * double(all.size()));
    bool rootIsLeaf = !root;
    if (rootIsLeaf) {
        // The root node then holds a single leaf child with every triangle.
        root = std::make_unique<TempNode>();
        if (!all.empty()) root->box[0] = sceneBox;
        root->subtreeRefs = all.size();
        root->subtreeWords = all.empty() ? 0 : TriangleStore::leafWords(uint32_t(all.size()));
        root->refs[0] = std::move(all);
    }
    std::vector<uint32_t>().swap(all);
    std::vector<BoundingBox3f>().swap(bounds);

    m_nodes.resize(root->subtreeNodes);
    m_nodes.shrink_to_fit();
    if (root->subtreeWords >= size_t(UINT32_MAX))
        throw NoriException("octree: the scene needs {} triangle references, too many for 32-bit offsets",
                            root->subtreeRefs);
    m_triangles.reset(m_intersector, root->subtreeWords);
    flatten(*root, 0, 0, m_nodes, m_triangles, vertices);

    // Statistics over the temporary tree (serial; a few ten thousand nodes).
    m_stats.refs = root->subtreeRefs;
    if (rootIsLeaf) {
        m_stats.leafNodes = 1;
        m_stats.emptyLeaves = root->subtreeRefs == 0;
        return;
    }
    std::vector<std::pair<const TempNode *, int>> stack{{root.get(), 0}};
    while (!stack.empty()) {
        auto [node, depth] = stack.back();
        stack.pop_back();
        ++m_stats.internalNodes;
        for (int c = 0; c < 8; ++c) {
            if (node->inner[c]) {
                stack.push_back({node->inner[c].get(), depth + 1});
                continue;
            }
            ++m_stats.leafNodes;
            if (node->refs[c].empty()) ++m_stats.emptyLeaves;
            m_stats.maxDepthReached = std::max(m_stats.maxDepthReached, depth + 1);
        }
    }
}

} // namespace nori
