/// \file area.cpp
/// \brief Area light (Nori's `area`): a mesh that emits constant radiance on one side.
#include <nori/emitter.h>
#include <nori/mesh.h>

namespace nori {

/// \brief Every point of the mesh emits `radiance` into the hemisphere its shading normal points
/// to (NORI-SPEC 6.5: the shipped furnace and table lights need the shading, not the winding,
/// normal). Points are sampled uniformly by area; densities are converted to solid angle with the
/// geometric normal, the true surface measure.
class AreaLight : public Emitter {
public:
    explicit AreaLight(const PropertyList &props) {
        m_radiance = props.getColor("radiance");
        if (!(m_radiance >= 0.0f).all()) props.fail("radiance", "radiance must not be negative");
    }

    Color3f eval(const EmitterQueryRecord &rec) const override {
        return rec.n.dot(rec.wi) < 0.0f ? m_radiance : Color3f(0.0f);
    }

    Color3f sample(EmitterQueryRecord &rec, const Point2f &sample) const override {
        MeshSample s;
        m_mesh->samplePosition(sample, s);
        rec.p = s.p;
        rec.n = s.n;
        rec.ng = s.ng;
        rec.offset = s.offset;
        Vector3f d = rec.p - rec.ref;
        float distance2 = d.squaredNorm();
        rec.distance = std::sqrt(distance2);
        rec.pdf = 0.0f;
        if (!(rec.distance > 0.0f)) return Color3f(0.0f);
        rec.wi = d / rec.distance;
        float cosine = std::abs(rec.ng.dot(rec.wi));
        if (!(cosine > 0.0f)) return Color3f(0.0f);
        rec.pdf = s.pdf * distance2 / cosine;
        if (!std::isfinite(rec.pdf)) {
            rec.pdf = 0.0f;
            return Color3f(0.0f);
        }
        return eval(rec) / rec.pdf;
    }

    float pdf(const EmitterQueryRecord &rec) const override {
        float cosine = std::abs(rec.ng.dot(rec.wi));
        if (!(cosine > 0.0f) || !(rec.distance > 0.0f)) return 0.0f;
        float pdf = rec.distance * rec.distance / (cosine * m_mesh->surfaceArea());
        return std::isfinite(pdf) ? pdf : 0.0f;
    }

    std::string toString() const override {
        return fmt::format("AreaLight[radiance=({}, {}, {})]", m_radiance[0], m_radiance[1], m_radiance[2]);
    }

private:
    Color3f m_radiance;
};

NORI_REGISTER_CLASS(AreaLight, "area", EEmitter);

} // namespace nori
