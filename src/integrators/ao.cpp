/// \file ao.cpp
/// \brief Ambient occlusion with cosine-weighted shadow rays (Nori's `ao`).
#include <nori/sampler.h>
#include <nori/scene.h>
#include <nori/warp.h>

namespace nori {

class AmbientOcclusion : public Integrator {
public:
    explicit AmbientOcclusion(const PropertyList &props) {
        m_samples = props.getInteger("samples", 1);
        if (m_samples <= 0 || m_samples > 4096) props.fail("samples", "samples must be in [1, 4096]");
        m_length = props.getFloat("length", Infinity);
        if (!(m_length > 0.0f)) props.fail("length", "length must be positive");
    }

    Color3f Li(const Scene &scene, Sampler &sampler, const Ray3f &ray) const override {
        Intersection its;
        if (!scene.rayIntersect(ray, its)) return Color3f(0.0f);
        // Occlusion of the hemisphere on the side the camera sees.
        Normal3f ng, ns;
        its.normalsFacing(ray.d, ng, ns);
        Frame frame(ns);
        int visible = 0;
        for (int i = 0; i < m_samples; ++i) {
            // Cosine-weighted directions: the estimator of (1/pi) * integral V cos is just V.
            Vector3f d = frame.toWorld(squareToCosineHemisphere(sampler.next2D()));
            if (d.dot(ng) <= 0.0f) continue;  // below the true surface: blocked by it
            if (!scene.rayIntersect(its.spawnRay(d, m_length))) ++visible;
        }
        return Color3f(float(visible) / float(m_samples));
    }

    std::string toString() const override { return fmt::format("AmbientOcclusion[samples={}]", m_samples); }

private:
    int m_samples;
    float m_length;
};

NORI_REGISTER_CLASS(AmbientOcclusion, "ao", EIntegrator);

} // namespace nori
