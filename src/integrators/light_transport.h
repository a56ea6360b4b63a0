/// \file light_transport.h
/// \brief Pieces the light-transport integrators share: emitter sampling at a surface point, the
/// emitter-sampling density of a point a ray has hit, and Russian roulette.
#pragma once

#include <nori/bsdf.h>
#include <nori/sampler.h>
#include <nori/scene.h>

namespace nori {

/// \brief One emitter-sampling estimate of the light reflected at a surface point.
struct DirectSample {
    Color3f value{0.0f, 0.0f, 0.0f};  ///< f * Le * |cos| / pdf, already zero when occluded
    float emitterPdf = 0.0f;         ///< solid-angle density of the sampled direction, choice of emitter included
    float bsdfPdf = 0.0f;            ///< the BSDF's density of the same direction (for MIS)
};

/// \brief Choose an emitter uniformly and a point on it uniformly by area, evaluate the BSDF at
/// \p its for the path arriving along \p wiWorld (pointing away from the surface, towards where the
/// path came from), and trace one shadow segment. Uses one 1D and one 2D sample.
DirectSample sampleDirect(const Scene &scene, Sampler &sampler, const Intersection &its, const BSDF &bsdf,
                          const Vector3f &wiWorld);

/// \brief Radiance emitted by the hit \p its towards \p from (zero if the mesh does not emit or
/// \p from is behind its emitting side).
Color3f emitted(const Intersection &its, const Point3f &from);

/// \brief Solid-angle density with which sampleDirect() from \p from would have chosen the hit \p its
/// (which must lie on an emitter).
float directPdf(const Scene &scene, const Point3f &from, const Intersection &its);

/// \brief Nori's Russian roulette (NORI-SPEC 7.7) after \p bounces bounces: from the fourth on, the
/// path survives with probability q = min(max(throughput) * eta^2, 0.99), and its throughput is
/// divided by q. \p eta is the product of the refraction ratios along the path. Returns false
/// when the path ends.
bool russianRoulette(Sampler &sampler, int bounces, float eta, Color3f &throughput);

/// \brief Bounces after which a path ends regardless (Russian roulette has long ended it by then:
/// surviving 10000 draws at q <= 0.99 has probability below 1e-43).
constexpr int MaxBounces = 10000;

} // namespace nori
