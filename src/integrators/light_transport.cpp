/// \file light_transport.cpp
/// \brief Emitter sampling, emitted radiance and Russian roulette for the path tracers.
#include "light_transport.h"

namespace nori {

DirectSample sampleDirect(const Scene &scene, Sampler &sampler, const Intersection &its, const BSDF &bsdf,
                          const Vector3f &wiWorld) {
    DirectSample result;
    float choice = sampler.next1D();
    Point2f position = sampler.next2D();
    const Emitter *emitter = scene.sampleEmitter(choice);
    if (!emitter) return result;
    EmitterQueryRecord eRec(its.p);
    Color3f radiance = emitter->sample(eRec, position);  // Le / pdf of this emitter
    if (!(eRec.pdf > 0.0f) || radiance.isZero()) return result;
    BSDFQueryRecord bRec(its.shFrame.toLocal(wiWorld), its.shFrame.toLocal(eRec.wi), EMeasure::SolidAngle);
    Color3f f = bsdf.eval(bRec);
    if (f.isZero()) return result;
    const float choicePdf = scene.emitterChoicePdf();
    result.emitterPdf = eRec.pdf * choicePdf;
    result.bsdfPdf = bsdf.pdf(bRec);
    if (scene.rayIntersect(its.spawnSegment(eRec.p, eRec.offset, eRec.ng))) return result;
    result.value = f * radiance * (std::abs(Frame::cosTheta(bRec.wo)) / choicePdf);
    return result;
}

Color3f emitted(const Intersection &its, const Point3f &from) {
    const Emitter *emitter = its.mesh->emitter();
    if (!emitter) return Color3f(0.0f);
    return emitter->eval(EmitterQueryRecord(from, its));
}

float directPdf(const Scene &scene, const Point3f &from, const Intersection &its) {
    const Emitter *emitter = its.mesh->emitter();
    if (!emitter) return 0.0f;
    return emitter->pdf(EmitterQueryRecord(from, its)) * scene.emitterChoicePdf();
}

bool russianRoulette(Sampler &sampler, int bounces, float eta, Color3f &throughput) {
    if (bounces < 4) return true;
    float q = std::min(throughput.maxCoeff() * eta * eta, 0.99f);
    if (!(q > 0.0f) || sampler.next1D() >= q) return false;
    throughput /= q;
    return true;
}

} // namespace nori
