/// \file path_mis.cpp
/// \brief Path tracing with multiple importance sampling (Nori's `path_mis`, PA5).
#include "light_transport.h"

namespace nori {

/// \brief Both strategies at every smooth vertex, combined with the balance heuristic (Veach 1997,
/// ch. 9) in solid angle: the emitter sample gets p_e / (p_e + p_b), emission hit by the BSDF-sampled
/// ray p_b / (p_e + p_b). After a specular vertex (no emitter sample there) the hit counts fully.
class PathMisIntegrator : public Integrator {
public:
    explicit PathMisIntegrator(const PropertyList &) {}

    Color3f Li(const Scene &scene, Sampler &sampler, const Ray3f &cameraRay) const override {
        Color3f result(0.0f), throughput(1.0f);
        float eta = 1.0f;
        bool previousSampledEmitters = false;
        float previousBsdfPdf = 0.0f;
        Point3f previous = cameraRay.o;
        Ray3f ray = cameraRay;
        for (int bounce = 0; bounce < MaxBounces; ++bounce) {
            Intersection its;
            if (!scene.rayIntersect(ray, its)) break;
            Color3f le = emitted(its, previous);
            if (!le.isZero()) {
                float w = 1.0f;
                if (previousSampledEmitters) {
                    float pe = directPdf(scene, previous, its);
                    w = previousBsdfPdf + pe > 0.0f ? previousBsdfPdf / (previousBsdfPdf + pe) : 0.0f;
                }
                result += throughput * w * le;
            }
            const BSDF &bsdf = *its.mesh->bsdf();
            const Vector3f toPrevious = -ray.d.normalized();
            previousSampledEmitters = bsdf.isDiffuse();
            if (previousSampledEmitters) {
                DirectSample direct = sampleDirect(scene, sampler, its, bsdf, toPrevious);
                if (!direct.value.isZero())
                    result += throughput * direct.value * (direct.emitterPdf / (direct.emitterPdf + direct.bsdfPdf));
            }
            BSDFQueryRecord bRec(its.shFrame.toLocal(toPrevious));
            Color3f weight = bsdf.sample(bRec, sampler.next2D());
            if (weight.isZero()) break;
            previousBsdfPdf = bRec.measure == EMeasure::SolidAngle ? bsdf.pdf(bRec) : 0.0f;
            throughput *= weight;
            eta *= bRec.eta;
            if (!russianRoulette(sampler, bounce + 1, eta, throughput)) break;
            previous = its.p;
            ray = its.spawnRay(its.shFrame.toWorld(bRec.wo));
        }
        return result;
    }

    std::string toString() const override { return "PathMisIntegrator[]"; }
};

NORI_REGISTER_CLASS(PathMisIntegrator, "path_mis", EIntegrator);

} // namespace nori
