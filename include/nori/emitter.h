/// \file emitter.h
/// \brief Light sources: emitted radiance, and sampling of points on them as seen from a point.
#pragma once

#include <nori/accel.h>
#include <nori/color.h>

namespace nori {

/// \brief A point on an emitter as seen from a reference point \c ref: filled by Emitter::sample(),
/// or by the constructor for a point a ray has hit.
struct EmitterQueryRecord {
    Point3f ref;           ///< the point being lit
    Point3f p;             ///< the point on the emitter
    Normal3f n;            ///< shading normal at p: decides the emitting side
    Normal3f ng;           ///< geometric normal at p: area-to-solid-angle conversion, ray offset
    float offset = 0.0f;   ///< spawn offset of p (see spawnOffset() in ray.h)
    Vector3f wi;           ///< unit direction from ref to p
    float distance = 0.0f; ///< |p - ref|
    float pdf = 0.0f;      ///< solid-angle density at ref of this emitter's sample() choosing p

    /// \brief A record to be filled by sample().
    explicit EmitterQueryRecord(const Point3f &ref) : ref(ref) {}
    /// \brief The point \p its that a ray from \p ref has hit.
    EmitterQueryRecord(const Point3f &ref, const Intersection &its)
        : ref(ref), p(its.p), n(its.shFrame.n), ng(its.geoFrame.n), offset(its.offset) {
        Vector3f d = p - ref;
        distance = d.norm();
        wi = distance > 0.0f ? Vector3f(d / distance) : Vector3f::Zero();
    }
};

/// \brief Base class of light sources.
class Emitter : public NoriObject {
public:
    /// \brief Choose a point given \c rec.ref (fills every field of \p rec) and return the radiance
    /// arriving at ref from it divided by rec.pdf, visibility not included; zero when the point
    /// does not light ref.
    virtual Color3f sample(EmitterQueryRecord &rec, const Point2f &sample) const = 0;
    /// \brief Radiance leaving rec.p towards rec.ref (zero on the side that does not emit).
    virtual Color3f eval(const EmitterQueryRecord &rec) const = 0;
    /// \brief Solid-angle density at rec.ref of sample() choosing rec.p.
    virtual float pdf(const EmitterQueryRecord &rec) const = 0;
    /// \brief The mesh this emitter covers (called by the mesh once it is complete).
    virtual void setMesh(const Mesh *mesh) { m_mesh = mesh; }
    const Mesh *mesh() const { return m_mesh; }

    EClassType getClassType() const override { return EEmitter; }

protected:
    const Mesh *m_mesh = nullptr;
};

} // namespace nori
