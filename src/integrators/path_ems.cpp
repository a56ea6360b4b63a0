/// \file path_ems.cpp
/// \brief Path tracing with emitter sampling (next-event estimation; Nori's `path_ems`, PA5).
#include "light_transport.h"

namespace nori {

/// \brief At every smooth vertex one emitter-sampling estimate; the path continues by BSDF
/// sampling. Emission found by a BSDF-sampled ray counts only when the previous vertex did not
/// sample emitters (the camera, or a specular surface), so no light is counted twice.
class PathEmsIntegrator : public Integrator {
public:
    explicit PathEmsIntegrator(const PropertyList &) {}

    Color3f Li(const Scene &scene, Sampler &sampler, const Ray3f &cameraRay) const override {
        Color3f result(0.0f), throughput(1.0f);
        float eta = 1.0f;
        bool countEmission = true;
        Ray3f ray = cameraRay;
        for (int bounce = 0; bounce < MaxBounces; ++bounce) {
            Intersection its;
            if (!scene.rayIntersect(ray, its)) break;
            if (countEmission) result += throughput * emitted(its, ray.o);
            const BSDF &bsdf = *its.mesh->bsdf();
            const Vector3f toPrevious = -ray.d.normalized();
            countEmission = !bsdf.isDiffuse();
            if (bsdf.isDiffuse()) result += throughput * sampleDirect(scene, sampler, its, bsdf, toPrevious).value;
            BSDFQueryRecord bRec(its.shFrame.toLocal(toPrevious));
            Color3f weight = bsdf.sample(bRec, sampler.next2D());
            if (weight.isZero()) break;
            throughput *= weight;
            eta *= bRec.eta;
            if (!russianRoulette(sampler, bounce + 1, eta, throughput)) break;
            ray = its.spawnRay(its.shFrame.toWorld(bRec.wo));
        }
        return result;
    }

    std::string toString() const override { return "PathEmsIntegrator[]"; }
};

NORI_REGISTER_CLASS(PathEmsIntegrator, "path_ems", EIntegrator);

} // namespace nori
