/// \file simple.cpp
/// \brief Direct light from one point light with a shadow ray (Nori's `simple`).
#include <nori/scene.h>

namespace nori {

class SimpleIntegrator : public Integrator {
public:
    explicit SimpleIntegrator(const PropertyList &props) {
        m_position = props.getPoint("position");
        m_energy = props.getColor("energy");
        if (!(m_energy >= 0.0f).all()) props.fail("energy", "energy must not be negative");
    }

    Color3f Li(const Scene &scene, Sampler &, const Ray3f &ray) const override {
        Intersection its;
        if (!scene.rayIntersect(ray, its)) return Color3f(0.0f);
        // Shade the side the camera sees.
        Normal3f ng, ns;
        its.normalsFacing(ray.d, ng, ns);
        Vector3f toLight = m_position - its.p;
        float distance2 = toLight.squaredNorm();
        float cosTheta = ns.dot(toLight) / std::sqrt(distance2);
        if (!(cosTheta > 0.0f)) return Color3f(0.0f);
        if (scene.rayIntersect(its.spawnRayTo(m_position))) return Color3f(0.0f);
        // Point light of power Phi seen by a white Lambertian surface: Phi / (4 pi) * (1 / pi) * cos / d^2.
        return m_energy * (InvFourPi * InvPi * cosTheta / distance2);
    }

    std::string toString() const override {
        return fmt::format("SimpleIntegrator[position=({}, {}, {})]", m_position.x(), m_position.y(), m_position.z());
    }

private:
    Point3f m_position;
    Color3f m_energy;
};

NORI_REGISTER_CLASS(SimpleIntegrator, "simple", EIntegrator);

} // namespace nori
