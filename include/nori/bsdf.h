/// \file bsdf.h
/// \brief Surface scattering model interface (Nori's contract: eval, pdf, sample).
#pragma once

#include <nori/color.h>
#include <nori/object.h>

namespace nori {

/// \brief The measure a BSDF value or density is expressed in.
enum class EMeasure {
    Unknown,     ///< not yet known (a record about to be sampled)
    SolidAngle,  ///< smooth scattering: densities per steradian
    Discrete,    ///< Dirac (specular) scattering: probabilities of single directions
};

/// \brief Query for a BSDF: directions in the local shading frame (z = shading normal), both
/// pointing away from the surface. \c wi is where the light-transport path comes from (the
/// camera side), \c wo where it continues.
struct BSDFQueryRecord {
    Vector3f wi;
    Vector3f wo;
    /// \brief Relative index of refraction of the sampled event: the index of the medium \c wo
    /// points into over that of the medium \c wi points into (1 for reflection). A refracted
    /// sample's weight includes the radiance scaling 1 / eta^2, so a path tracer that keeps the
    /// product of the etas along the path and applies Russian roulette to throughput * eta^2
    /// decides on the path's unscaled throughput.
    float eta = 1.0f;
    EMeasure measure = EMeasure::Unknown;

    /// \brief A record for sampling: only \p wi is known.
    explicit BSDFQueryRecord(const Vector3f &wi) : wi(wi) {}
    /// \brief A record for evaluating the pair (\p wi, \p wo) in \p measure.
    BSDFQueryRecord(const Vector3f &wi, const Vector3f &wo, EMeasure measure) : wi(wi), wo(wo), measure(measure) {}
};

/// \brief A BSDF evaluated in the local shading frame.
class BSDF : public NoriObject {
public:
    /// \brief Sample \c wo given \c bRec.wi and a uniform 2D \p sample; fills wo, measure and eta.
    /// Returns the importance weight eval * cos(theta_o) / pdf (no cosine for discrete measure),
    /// or zero when sampling failed.
    virtual Color3f sample(BSDFQueryRecord &bRec, const Point2f &sample) const = 0;
    /// \brief BSDF value for the pair in \c bRec (zero for a discrete BSDF).
    virtual Color3f eval(const BSDFQueryRecord &bRec) const = 0;
    /// \brief Density of sample() producing \c bRec.wo, in \c bRec.measure (zero for a discrete BSDF).
    virtual float pdf(const BSDFQueryRecord &bRec) const = 0;
    /// \brief Smooth scattering that emitter sampling can handle (diffuse, microfacet); false for
    /// specular (Dirac) BSDFs.
    virtual bool isDiffuse() const { return false; }

    EClassType getClassType() const override { return EBSDF; }
};

} // namespace nori
