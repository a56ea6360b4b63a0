/// \file octree_build.h
/// \brief The octree's construction in two steps: a recursive midpoint subdivision into a
/// temporary tree (octree_build.cpp), then its flattening into the node array and the triangle
/// store (octree_layout.cpp).
#pragma once

#include "huge_pages.h"
#include "octree.h"
#include <array>
#include <memory>
#include <vector>

namespace nori::octree_build {

/// \brief What the subdivision reads.
struct Input {
    const std::array<Point3f, 3> *vertices;  ///< corners of every global triangle
    const float *areas;                       ///< twice the area of every global triangle
    OctreeAccel::BuildRule rule;
    int maxDepth;
    size_t leafSize;
    bool exact;  ///< separating-axis test for triangles whose box straddles a midplane
    bool termination = true;  ///< `sah`: price a split's children by the rays that reach them (see split())
    bool lookahead = true;    ///< `sah`: build a rejected split whose one child may pay as a subtree (see split())
};

/// A reference is a global triangle id; the `sah` rule marks with this bit the triangles that
/// went down loose (not copied; their bounds are no longer clipped to the cell).
constexpr uint32_t kLooseBit = 0x80000000u;

/// \brief A triangle reference during the build: its id (with a mark for the `sah` rule's
/// loose triangles) and its bounds, carried along so that classifying a node's triangles reads
/// one array in order instead of the bounds of scattered ids (the build's cache misses). Plain
/// floats: arrays of them are allocated without being initialised first.
struct Ref {
    float lo[3], hi[3];  ///< the triangle's own bounds (not clipped)
    uint32_t id;
};

/// \brief A leaf's triangle ids (global), in storage its node owns.
struct LeafIds {
    const uint32_t *ids = nullptr;
    size_t count = 0;
    const uint32_t *data() const { return ids; }
    size_t size() const { return count; }
    bool empty() const { return count == 0; }
};

/// \brief An inner node of the temporary tree. Child slot c (see OctreeNode::Pattern) is an
/// inner node (inner[c]), a leaf (refs[c] non-empty) or empty.
struct TempNode {
    BoundingBox3f box[8];  ///< tight child boxes
    std::unique_ptr<TempNode> inner[8];
    LeafIds refs[8];
    LargeArray<uint32_t> leafIds;  ///< the ids of all its leaves, one block (refs[c] point into it)
    std::vector<uint32_t> kept;  ///< large triangles tested at this node, group after group
    /// The groups of kept: how many of its triangles each holds (in order) and their bounds.
    struct KeptGroup {
        uint32_t count;
        BoundingBox3f box;
    };
    std::vector<KeptGroup> keptGroups;
    OctreeNode::Pattern pattern{{0, 1, 2}};
    int childDepth[8] = {};   ///< depth of each child as the build rule counts it
    size_t subtreeNodes = 1;  ///< inner nodes in this subtree, this one included
    size_t subtreeRefs = 0;   ///< triangle references in this subtree (leaves and kept lists)
    size_t subtreeWords = 0;  ///< TriangleStore words of this subtree
    size_t subtreeGroups = 0; ///< kept groups in this subtree beyond each node's first
    double cost = 0.0;        ///< (`sah`) the cost model's price of this subtree for a ray entering its box
};

/// \brief The bisections that make the children of \p cell under \p rule (see
/// OctreeNode::Pattern), and the cell of child slot \p c.
OctreeNode::Pattern splitPattern(OctreeAccel::BuildRule rule, const BoundingBox3f &cell);
BoundingBox3f childCell(const BoundingBox3f &cell, const OctreeNode::Pattern &p, int c);
/// \brief The bisections the `sah` rule chooses for a node of \p cell whose triangles have
/// the bounding boxes \p bounds and fill \p box (other rules: splitPattern(rule, cell)).
OctreeNode::Pattern splitPattern(OctreeAccel::BuildRule rule, const BoundingBox3f &cell, const BoundingBox3f &box,
                                 const std::vector<BoundingBox3f> &bounds);

/// \brief Subdivide \p cell (holding the \p n triangles \p refs, whose bounds clipped to the
/// cell are \p box; the array is reordered and overwritten), the root at depth 0. Returns null
/// when the root is best left a single leaf.
std::unique_ptr<TempNode> subdivide(const Input &in, const BoundingBox3f &cell, const BoundingBox3f &box, Ref *refs,
                                    size_t n);

} // namespace nori::octree_build
