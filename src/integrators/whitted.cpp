/// \file whitted.cpp
/// \brief Whitted-style ray tracing with area lights (Nori's `whitted`, PA4).
#include "light_transport.h"

namespace nori {

/// \brief Emission at every hit; at a diffuse (smooth) surface one emitter-sampling estimate ends
/// the path; at a specular one the BSDF is sampled and the path continues with probability 0.95
/// (its weight divided by 0.95), so specular chains of any length stay unbiased.
class WhittedIntegrator : public Integrator {
public:
    explicit WhittedIntegrator(const PropertyList &) {}

    Color3f Li(const Scene &scene, Sampler &sampler, const Ray3f &cameraRay) const override {
        Color3f result(0.0f), throughput(1.0f);
        Ray3f ray = cameraRay;
        for (int bounce = 0; bounce < MaxBounces; ++bounce) {
            Intersection its;
            if (!scene.rayIntersect(ray, its)) break;
            result += throughput * emitted(its, ray.o);
            const BSDF &bsdf = *its.mesh->bsdf();
            const Vector3f toCamera = -ray.d.normalized();
            if (bsdf.isDiffuse()) {
                result += throughput * sampleDirect(scene, sampler, its, bsdf, toCamera).value;
                break;
            }
            BSDFQueryRecord bRec(its.shFrame.toLocal(toCamera));
            Color3f weight = bsdf.sample(bRec, sampler.next2D());
            if (weight.isZero() || sampler.next1D() >= ContinuationProbability) break;
            throughput *= weight / ContinuationProbability;
            ray = its.spawnRay(its.shFrame.toWorld(bRec.wo));
        }
        return result;
    }

    std::string toString() const override { return "WhittedIntegrator[]"; }

private:
    static constexpr float ContinuationProbability = 0.95f;
};

NORI_REGISTER_CLASS(WhittedIntegrator, "whitted", EIntegrator);

} // namespace nori
