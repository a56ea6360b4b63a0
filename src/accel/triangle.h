/// \file triangle.h
/// \brief Ray/triangle intersectors (Möller–Trumbore, watertight) and the precomputed
/// triangle store that the octree leaves and the brute-force accel both test.
///
/// All arithmetic lives in src/accel/triangle.cpp, written once over lanes::VFloat<L> (16, 8 and
/// 1 lanes) and compiled with -ffp-contract=off: the watertight test needs `a*b - c*d` evaluated
/// without a fused multiply-add (an FMA rounds the two products differently, so the edge
/// functions of two triangles sharing an edge would no longer be exact negatives), and every
/// width and every accelerator must get bit-identical results from the same store (so that ties
/// and near-ties resolve the same way in brute force and octree, on every machine).
#pragma once

#include <nori/accel.h>
#include "huge_pages.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace nori {

/// \brief Which ray/triangle test a store runs.
enum class Intersector {
    MT,          ///< Möller & Trumbore 1997; fast, may leak through shared edges
    Watertight,  ///< Woop, Benthin & Wald 2013 (JCGT 2(1)); no leaks through shared edges/vertices
};

/// \brief Parse "mt" / "watertight"; throws through \p props.fail for anything else.
Intersector parseIntersector(const PropertyList &props, const std::string &defaultValue);
/// \brief "mt" or "watertight".
const char *intersectorName(Intersector kind);

/// \brief Whether any ray can hit the triangle with corners \p v. Not when a corner is not
/// finite, nor when the corners lie on one line, decided exactly (exactlyCollinear(): a point,
/// a segment; the watertight test never finds a crossing inside it). Every accelerator leaves
/// such triangles out: no answer changes, and the watertight test would otherwise send every
/// lane of a point-like triangle, all of whose edge functions are zero, to exact arithmetic.
bool triangleCanBeHit(const std::array<Point3f, 3> &v);

/// \brief Per-ray constants of both intersectors, computed once per query.
struct TriangleRay {
    float o[3], d[3];
    float mint;
    // Watertight: kz is the dominant axis of d; (kx, ky) the other two, swapped when d[kz] < 0
    // to keep the winding; the shear maps d to (0, 0, 1) in (kx, ky, kz) coordinates.
    int kx, ky, kz;
    float sx, sy, sz;
    // Chunk boxes: conservative slab test (entry rounded down, exit up).
    float rcpNear[3], rcpFar[3];
    int neg[3];
    /// 2^-18 of |o|_inf / |d|_inf: with 2^-18 |t|, twice the float t error the kernels accept
    /// before they recompute t in double (needsExactT).
    float cullAbs;

    explicit TriangleRay(const Ray3f &ray) : TriangleRay(ray, cullAbsOf(ray)) {}
    /// \brief The same with cullAbs (cullAbsOf(ray)) known already.
    TriangleRay(const Ray3f &ray, float cullAbs);

    /// \brief Boxes entered beyond this are culled while \p best is the closest hit so far. A
    /// triangle's float t may lie below its exact t by up to the kernels' tolerance, so a box
    /// entered just beyond best may still hold a triangle whose float t is below best; culling
    /// only past the tolerance makes the answer independent of the order in which an
    /// accelerator meets the triangles (octree and brute force agree bit for bit).
    float cullLimit(float best) const { return cullLimitOf(best, cullAbs); }
    static float cullLimitOf(float best, float cullAbs) { return best + (0x1p-18f * std::abs(best) + cullAbs); }
    /// \brief cullAbs of \p ray, without the rest of the setup (|d[kz]| is the largest |d|).
    /// 1 / |d|_inf is the smallest |dRcp|: division rounds monotonically, so min_a fl(1 / |d_a|)
    /// = fl(1 / max_a |d_a|) bit for bit, without a division on the way to the first node test.
    static float cullAbsOf(const Ray3f &ray) {
        const float maxO = std::max({std::abs(ray.o.x()), std::abs(ray.o.y()), std::abs(ray.o.z())});
        const float rcpMaxD = std::min({std::abs(ray.dRcp.x()), std::abs(ray.dRcp.y()), std::abs(ray.dRcp.z())});
        return 0x1p-18f * maxO * rcpMaxD;
    }
};

/// \brief Triangles of all meshes, copied in the order the accelerator's leaves visit them.
///
/// A leaf of n triangles is one block of words at an offset chosen by its owner: nine rows of
/// n floats (the corners v0, v1, v2, each row x, y, z, for both intersectors: either may
/// recompute t on the exact triangle), then the n global triangle ids, then (for n > 16) one
/// bounding box per block of blockSize(n) triangles. Structure-of-arrays rows let the SIMD kernels load
/// 16 triangles with masked loads and no padding; the triangles of a leaf are ordered so that each
/// block is spatially compact, and a block whose box the ray misses is skipped.
class TriangleStore {
public:
    /// \brief Triangles per box of a leaf of \p n > 16 triangles. Up to 128 triangles (16 boxes,
    /// one 16-lane box test), half a 16-lane step: a ray that enters one of two neighbouring
    /// blocks pays an 8-lane step (on cores that split a 16-lane operation in two halves, half
    /// the work), one that enters both a 16-lane step. Larger leaves (thin triangles that no
    /// split separates: grass) keep one box per 16: twice the boxes would cost more to test
    /// and order than the half steps save.
    static constexpr uint32_t blockSize(uint32_t n) { return 1u << blockShift(n); }
    static constexpr uint32_t blockShift(uint32_t n) { return n <= 128 ? 3 : 4; }
    /// \brief Boxes of a leaf of \p n triangles (a shift, not a division: on the hot path).
    static constexpr uint32_t blockCount(uint32_t n) { return n > 16 ? (n + blockSize(n) - 1) >> blockShift(n) : 0; }
    /// \brief Words (4 bytes) taken by a leaf of \p n triangles.
    static size_t leafWords(uint32_t n) { return size_t(10) * n + size_t(6) * blockCount(n); }

    /// \brief Allocate \p words words for intersector \p kind.
    void reset(Intersector kind, size_t words);
    /// \brief Write a leaf at word \p offset from the global ids \p prims (thread-safe for
    /// disjoint leaves). \p vertices holds the three corners of every global triangle. With
    /// \p clip (an octree leaf's box: every hit the leaf must report lies in it), the chunk
    /// boxes hold only the triangles' bounds within it.
    void setLeaf(size_t offset, const uint32_t *prims, uint32_t n, const std::vector<std::array<Point3f, 3>> &vertices,
                 const BoundingBox3f *clip = nullptr) {
        setLeaf(offset, prims, n, vertices.data(), clip);
    }
    /// \brief The same with the corners in any array (indexed by global id).
    void setLeaf(size_t offset, const uint32_t *prims, uint32_t n, const std::array<Point3f, 3> *vertices,
                 const BoundingBox3f *clip = nullptr);

    /// \brief Closest hit among the leaf's triangles with t in [ray.mint, best.t]; a hit at
    /// exactly best.t wins only with a lower triangle id (deterministic ties). Updates \p best.
    bool intersect(const TriangleRay &ray, size_t offset, uint32_t n, Hit &best) const;
    /// \brief Is any triangle of the leaf hit with t in [ray.mint, maxt]?
    bool occluded(const TriangleRay &ray, size_t offset, uint32_t n, float maxt) const;

    // The same kernels at a chosen lane count (for tests: every width must agree bit for bit).
    /// \brief Lane counts compiled into this build, widest first: 16 (AVX-512), 8 (AVX2), 1.
    static std::vector<int> laneWidths();
    /// \brief intersect() with one lane (the reference all widths must match bit for bit).
    bool intersectReference(const TriangleRay &ray, size_t offset, uint32_t n, Hit &best) const;
    /// \brief intersect() / occluded() with \p lanes lanes (one of laneWidths(), else throws).
    bool intersectLanes(int lanes, const TriangleRay &ray, size_t offset, uint32_t n, Hit &best) const;
    bool occludedLanes(int lanes, const TriangleRay &ray, size_t offset, uint32_t n, float maxt) const;
    /// \brief Each triangle's own decision in chunk k (triangles 16k .. 16k + 15) of a leaf.
    struct ChunkAnswers {
        unsigned hits;  ///< bit i: triangle 16k + i is hit with t in [ray.mint, maxt]
        /// bit i: t of triangle 16k + i came from the plane equation in double, and the
        /// kernel's barycentrics cleared their error bound, so the double inside test was skipped
        /// (the crossing must then lie strictly inside the triangle)
        unsigned insideKnown;
        float t[16], u[16], v[16];  ///< the kernel's values (meaningful where hit)
    };
    /// \brief Fill \p out for chunk \p k with \p lanes lanes; returns out.hits.
    unsigned chunkAnswers(int lanes, const TriangleRay &ray, size_t offset, uint32_t n, uint32_t k, float maxt,
                          ChunkAnswers &out) const;

    Intersector kind() const { return m_kind; }
    /// \brief Bytes owned.
    size_t bytes() const { return m_data.capacity() * sizeof(float); }

private:
    Intersector m_kind = Intersector::Watertight;
    /// resize() leaves the words uninitialised: setLeaf() writes every word of the store, so
    /// filling it with zeros first only cost a pass over it (3 % of the octree's build); on huge
    /// pages (allocateLarge()).
    std::vector<float, HugePageAllocator<float, false>> m_data;  ///< leaf blocks (ids stored as their bit patterns)
};

} // namespace nori
