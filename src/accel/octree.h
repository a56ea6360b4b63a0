/// \file octree.h
/// \brief `<accel type="octree">`: a midpoint-split octree over the triangles of all meshes,
/// with tight child boxes, flat node storage and several traversals.
#pragma once

#include "triangle.h"
#include <string>
#include <vector>

namespace nori {

/// \brief One inner node: the tight boxes of its eight children (each the union of its
/// triangles' bounding boxes clipped to the child's cell) and where each child lives.
/// 256 bytes, one 64-byte line per axis plus one for the child references.
struct alignas(64) OctreeNode {
    /// box[axis][c] is the lower bound of child c, box[axis][8 + c] its upper bound, so one
    /// 16-lane load per axis fetches both slabs of all eight children. An empty child has
    /// lower = +inf and upper = -inf: no ray ever enters it.
    float box[3][16];
    /// Inner child: index into the node array (count[c] == 0). Leaf: word offset of its block
    /// in the TriangleStore (count[c] > 0 triangles).
    uint32_t child[8];
    uint32_t count[8];
};
static_assert(sizeof(OctreeNode) == 256, "OctreeNode must be 4 cache lines");

/// \brief Octree accelerator. Properties (defaults measured on the 871k dragon): `maxDepth`
/// (16), `leafSize` (512: a node with fewer triangles is a leaf), `overlap` (bbox | exact*),
/// `traversal` (seed | sorted | simd*), `intersector` (mt | watertight*).
///
/// Build (octree_build.cpp): midpoint split of the cell, triangles classified against the
/// midplanes by their bounding boxes, the separating-axis test only for those that straddle;
/// children built as parallel TBB tasks; subdivision stops at maxDepth, below leafSize, and
/// when a split makes no progress or would exceed the reference budget (at most 8 references
/// per triangle for any input). Memory: 256-byte inner nodes only, leaves live in the
/// TriangleStore (40 bytes per reference plus 24 bytes per 16-triangle chunk).
///
/// Traversal (octree_traversal.cpp): every traversal culls a child whose entry distance lies
/// beyond the closest hit so far and never stops early (except `seed`), so the first-found
/// hit in a leaf may lie outside that leaf's cell without breaking exactness. Leaves test their
/// triangles sixteen at a time, nearest chunk first (TriangleStore).
class OctreeAccel : public Accel {
public:
    /// \brief How children are visited.
    enum class Traversal {
        Seed,    ///< children by distance to their box, stop at the first subtree that hits (inexact)
        Sorted,  ///< exact: children sorted by entry t, skip those beyond the closest hit
        Simd,    ///< exact: all eight boxes in one AVX-512 slab test, visited in the ray's octant order
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

    // Settings.
    int m_maxDepth;
    int m_leafSize;
    Overlap m_overlap;
    Traversal m_traversal;
    Intersector m_intersector;

    // Structure: node 0 is the root (always an inner node).
    std::vector<OctreeNode> m_nodes;
    TriangleStore m_triangles;

    // Statistics of the last build.
    struct Stats {
        size_t internalNodes = 0, leafNodes = 0, emptyLeaves = 0, refs = 0;
        int maxDepthReached = 0;
    } m_stats;
};

} // namespace nori
