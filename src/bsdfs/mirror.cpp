/// \file mirror.cpp
/// \brief Ideal specular reflector (Nori's `mirror`): a Dirac BSDF with reflectance 1.
#include <nori/bsdf.h>
#include <nori/fresnel.h>

namespace nori {

/// \brief Perfect mirror about the shading normal; eval and pdf are zero (discrete measure).
class Mirror : public BSDF {
public:
    explicit Mirror(const PropertyList &) {}

    Color3f eval(const BSDFQueryRecord &) const override { return Color3f(0.0f); }
    float pdf(const BSDFQueryRecord &) const override { return 0.0f; }

    Color3f sample(BSDFQueryRecord &bRec, const Point2f &) const override {
        // The back side is not a mirror (one-sided, like Nori's).
        if (bRec.wi.z() <= 0.0f) return Color3f(0.0f);
        bRec.wo = reflectLocal(bRec.wi);
        bRec.measure = EMeasure::Discrete;
        bRec.eta = 1.0f;
        return Color3f(1.0f);  // Dirac: no cosine, probability 1
    }

    std::string toString() const override { return "Mirror[]"; }
};

NORI_REGISTER_CLASS(Mirror, "mirror", EBSDF);

} // namespace nori
