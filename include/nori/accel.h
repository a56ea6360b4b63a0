/// \file accel.h
/// \brief Ray-intersection acceleration structure interface (closest hit and any hit).
#pragma once

#include <nori/frame.h>
#include <nori/mesh.h>
#include <nori/ray.h>
#include <utility>
#include <vector>

namespace nori {

/// \brief The raw result of a closest-hit query: parameter, barycentrics and global triangle id.
struct Hit {
    float t = Infinity;
    float u = 0.0f, v = 0.0f;  ///< barycentrics of corners 1 and 2
    uint32_t prim = ~0u;       ///< index into the accel's global triangle numbering
};

/// \brief Everything an integrator needs to know about a surface hit.
struct Intersection {
    Point3f p;
    /// \brief Distance along geoFrame.n by which a ray leaving p must start off the surface
    /// (rounding of p and the intersectors' own error; see spawnOffset() in ray.h).
    float offset = 0.0f;
    float t = Infinity;
    Point2f uv;          ///< texture coordinates (barycentrics if the mesh has none)
    Frame shFrame;       ///< shading frame (interpolated normal if the mesh has normals)
    Frame geoFrame;      ///< geometric frame
    const Mesh *mesh = nullptr;
    uint32_t triIndex = 0;  ///< triangle index within \p mesh

    /// \brief Geometric and shading normals flipped to the side that a ray along \p d sees.
    void normalsFacing(const Vector3f &d, Normal3f &ng, Normal3f &ns) const {
        float sign = geoFrame.n.dot(d) > 0.0f ? -1.0f : 1.0f;
        ng = sign * geoFrame.n;
        ns = sign * shFrame.n;
    }

    /// \brief A ray leaving the surface along \p d (to the side \p d points into), up to \p maxt.
    Ray3f spawnRay(const Vector3f &d, float maxt = Infinity) const {
        return nori::spawnRay(p, offset, geoFrame.n, d, maxt);
    }
    /// \brief A segment to the point \p q in free space (a point light): maxt = 1 is \p q.
    Ray3f spawnRayTo(const Point3f &q) const {
        Point3f o = offsetRayOrigin(p, offset, geoFrame.n, q - p);
        return Ray3f(o, q - o, 0.0f, 1.0f);
    }
    /// \brief A shadow segment to the point \p q of another surface (spawn offset \p qOffset,
    /// geometric normal \p qng); see nori::spawnSegment.
    Ray3f spawnSegment(const Point3f &q, float qOffset, const Normal3f &qng) const {
        return nori::spawnSegment(p, offset, geoFrame.n, q, qOffset, qng);
    }
};

/// \brief One named statistic of a built accelerator (printed by --stats, written as JSON).
struct AccelStat {
    std::string name;
    double value;
    bool integral;  ///< print without decimals
};

/// \brief Base class of accelerators. Triangles of all meshes are numbered globally in
/// the order the meshes were added.
class Accel : public NoriObject {
public:
    /// \brief Register a mesh (not owned); must be called before build().
    void addMesh(const Mesh *mesh);
    /// \brief Build the structure over all registered meshes and time it.
    void build();
    /// \brief Nori's query: closest hit (fills \p its) or, with \p shadowRay, any hit.
    bool rayIntersect(const Ray3f &ray, Intersection &its, bool shadowRay) const;

    /// \brief Closest hit in [ray.mint, ray.maxt]; on success fills \p hit.
    virtual bool intersect(const Ray3f &ray, Hit &hit) const = 0;
    /// \brief Any hit in [ray.mint, ray.maxt]: stops at the first one found.
    virtual bool occluded(const Ray3f &ray) const = 0;
    /// \brief Build statistics; the base adds build_ms and triangles.
    virtual std::vector<AccelStat> statistics() const;

    /// \brief Fill the surface data of \p its from a raw hit.
    void completeIntersection(const Ray3f &ray, const Hit &hit, Intersection &its) const;
    /// \brief Mesh and local triangle index of global triangle \p prim.
    std::pair<const Mesh *, uint32_t> locate(uint32_t prim) const;

    uint32_t triangleCount() const { return m_offsets.empty() ? 0 : m_offsets.back(); }
    const BoundingBox3f &bbox() const { return m_bbox; }
    const std::vector<const Mesh *> &meshes() const { return m_meshes; }
    double buildMilliseconds() const { return m_buildMs; }
    /// \brief CPU time of the calling thread during the last build (nori-bench --cpu-time: a
    /// figure a shared machine's other processes do not inflate, when the build is single-threaded).
    double buildCpuMilliseconds() const { return m_buildCpuMs; }

    EClassType getClassType() const override { return EAccel; }

protected:
    /// \brief Build the structure; meshes, offsets and bbox are ready.
    virtual void buildImpl() = 0;

    std::vector<const Mesh *> m_meshes;
    std::vector<uint32_t> m_offsets{0};  ///< prefix sums of triangle counts
    BoundingBox3f m_bbox;
    double m_buildMs = 0.0;
    double m_buildCpuMs = 0.0;
};

} // namespace nori
