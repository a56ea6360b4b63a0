/// \file path_mats.cpp
/// \brief Path tracing with BSDF sampling only (Nori's `path_mats`, PA5).
#include "light_transport.h"

namespace nori {

/// \brief Every vertex adds the emission it sees; the path continues by sampling the BSDF and
/// ends by Russian roulette. Light is found only by hitting it.
class PathMatsIntegrator : public Integrator {
public:
    explicit PathMatsIntegrator(const PropertyList &) {}

    Color3f Li(const Scene &scene, Sampler &sampler, const Ray3f &cameraRay) const override {
        Color3f result(0.0f), throughput(1.0f);
        float eta = 1.0f;
        Ray3f ray = cameraRay;
        for (int bounce = 0; bounce < MaxBounces; ++bounce) {
            Intersection its;
            if (!scene.rayIntersect(ray, its)) break;
            result += throughput * emitted(its, ray.o);
            BSDFQueryRecord bRec(its.shFrame.toLocal(-ray.d.normalized()));
            Color3f weight = its.mesh->bsdf()->sample(bRec, sampler.next2D());
            if (weight.isZero()) break;
            throughput *= weight;
            eta *= bRec.eta;
            if (!russianRoulette(sampler, bounce + 1, eta, throughput)) break;
            ray = its.spawnRay(its.shFrame.toWorld(bRec.wo));
        }
        return result;
    }

    std::string toString() const override { return "PathMatsIntegrator[]"; }
};

NORI_REGISTER_CLASS(PathMatsIntegrator, "path_mats", EIntegrator);

} // namespace nori
