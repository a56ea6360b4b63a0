/// \file dielectric.cpp
/// \brief Smooth dielectric interface (Nori's `dielectric`): Fresnel-weighted choice between
/// specular reflection and Snell refraction.
#include <nori/bsdf.h>
#include <nori/fresnel.h>

namespace nori {

/// \brief Glass-like boundary between \c extIOR (the side the shading normal points into) and
/// \c intIOR. Both events are Dirac, so eval and pdf are zero.
///
/// Radiance convention: radiance divided by eta^2 is what is conserved across a refraction, so
/// the refracted weight carries (eta_wi / eta_wo)^2 and bRec.eta is eta_wo / eta_wi (see
/// BSDFQueryRecord::eta). A path that enters and leaves a closed object collects the factors
/// (1/eta)^2 and eta^2, which cancel; Russian roulette on throughput * eta^2 sees the path's
/// unscaled throughput.
class Dielectric : public BSDF {
public:
    explicit Dielectric(const PropertyList &props) {
        // Nori's defaults: BK7 glass inside, air outside.
        m_intIOR = props.getFloat("intIOR", 1.5046f);
        m_extIOR = props.getFloat("extIOR", 1.000277f);
        if (!(m_intIOR > 0.0f)) props.fail("intIOR", fmt::format("intIOR must be positive, got {}", m_intIOR));
        if (!(m_extIOR > 0.0f)) props.fail("extIOR", fmt::format("extIOR must be positive, got {}", m_extIOR));
    }

    Color3f eval(const BSDFQueryRecord &) const override { return Color3f(0.0f); }
    float pdf(const BSDFQueryRecord &) const override { return 0.0f; }

    Color3f sample(BSDFQueryRecord &bRec, const Point2f &sample) const override {
        const float cosThetaI = bRec.wi.z();
        const float reflectance = fresnelDielectric(cosThetaI, m_extIOR, m_intIOR);
        bRec.measure = EMeasure::Discrete;
        // Choose reflection with probability F: the weight F / F is 1.
        if (sample.x() < reflectance) {
            bRec.wo = reflectLocal(bRec.wi);
            bRec.eta = 1.0f;
            return Color3f(1.0f);
        }
        const bool outside = cosThetaI >= 0.0f;
        const float etaWi = outside ? m_extIOR : m_intIOR;
        const float etaWo = outside ? m_intIOR : m_extIOR;
        // F < 1 here, so there is no total internal reflection; refractLocal agrees up to
        // rounding, and a disagreement falls back to the mirror direction.
        if (!refractLocal(bRec.wi, etaWi / etaWo, bRec.wo)) {
            bRec.wo = reflectLocal(bRec.wi);
            bRec.eta = 1.0f;
            return Color3f(1.0f);
        }
        bRec.eta = etaWo / etaWi;
        // (1 - F) / (1 - F) times the radiance scaling across the interface.
        const float scale = etaWi / etaWo;
        return Color3f(scale * scale);
    }

    std::string toString() const override {
        return fmt::format("Dielectric[intIOR={}, extIOR={}]", m_intIOR, m_extIOR);
    }

private:
    float m_intIOR, m_extIOR;
};

NORI_REGISTER_CLASS(Dielectric, "dielectric", EBSDF);

} // namespace nori
