/// \file microfacet.cpp
/// \brief Nori's `microfacet` BSDF: a Lambertian base plus a rough dielectric coating reflection
/// (Beckmann normals, Smith shadowing), as the PA5 assignment defines it.
#include <nori/bsdf.h>
#include <nori/frame.h>
#include <nori/fresnel.h>
#include <nori/warp.h>

namespace nori {

/// \brief f = kd/pi + ks D(h) F(h.wi) G(wi, wo, h) / (4 cos(theta_i) cos(theta_o) cos(theta_h)),
/// with ks = 1 - max(kd). D is the Beckmann density of warp.h (which already contains one
/// cos(theta_h), hence the extra one in the denominator); G is Smith's G1(wi) G1(wo) with the
/// rational approximation of Walter et al. 2007, eq. 27. Sampling picks the specular lobe
/// with probability ks (half-vector from the Beckmann warp, mirrored wi) and the diffuse lobe
/// otherwise (cosine-weighted).
class Microfacet : public BSDF {
public:
    explicit Microfacet(const PropertyList &props) {
        m_alpha = props.getFloat("alpha", 0.1f);
        m_intIOR = props.getFloat("intIOR", 1.5046f);
        m_extIOR = props.getFloat("extIOR", 1.000277f);
        m_kd = props.getColor("kd", Color3f(0.5f));
        if (!(m_alpha > 0.0f)) props.fail("alpha", fmt::format("alpha must be positive, got {}", m_alpha));
        if (!(m_intIOR > 0.0f)) props.fail("intIOR", fmt::format("intIOR must be positive, got {}", m_intIOR));
        if (!(m_extIOR > 0.0f)) props.fail("extIOR", fmt::format("extIOR must be positive, got {}", m_extIOR));
        // ks = 1 - max(kd) must be a probability, so kd lies in [0, 1].
        if (!(m_kd >= 0.0f).all() || !(m_kd <= 1.0f).all())
            props.fail("kd", fmt::format("kd components must be in [0, 1], got ({}, {}, {})", m_kd[0], m_kd[1], m_kd[2]));
        m_ks = 1.0f - m_kd.maxCoeff();
    }

    Color3f eval(const BSDFQueryRecord &bRec) const override {
        const float cosI = Frame::cosTheta(bRec.wi), cosO = Frame::cosTheta(bRec.wo);
        if (bRec.measure != EMeasure::SolidAngle || cosI <= 0.0f || cosO <= 0.0f) return Color3f(0.0f);
        const Vector3f wh = (bRec.wi + bRec.wo).normalized();
        const float D = squareToBeckmannPdf(wh, m_alpha);
        const float F = fresnelDielectric(wh.dot(bRec.wi), m_extIOR, m_intIOR);
        const float G = smithG1(bRec.wi, wh) * smithG1(bRec.wo, wh);
        const float specular = m_ks * D * F * G / (4.0f * cosI * cosO * Frame::cosTheta(wh));
        return m_kd * InvPi + Color3f(specular);
    }

    float pdf(const BSDFQueryRecord &bRec) const override {
        const float cosI = Frame::cosTheta(bRec.wi), cosO = Frame::cosTheta(bRec.wo);
        if (bRec.measure != EMeasure::SolidAngle || cosI <= 0.0f || cosO <= 0.0f) return 0.0f;
        const Vector3f wh = (bRec.wi + bRec.wo).normalized();
        // Reflecting about wh maps half-vector density to wo density with 1 / (4 wh.wo).
        const float specular = squareToBeckmannPdf(wh, m_alpha) / (4.0f * wh.dot(bRec.wo));
        return m_ks * specular + (1.0f - m_ks) * cosO * InvPi;
    }

    Color3f sample(BSDFQueryRecord &bRec, const Point2f &sample) const override {
        if (Frame::cosTheta(bRec.wi) <= 0.0f) return Color3f(0.0f);
        bRec.measure = EMeasure::SolidAngle;
        bRec.eta = 1.0f;
        // The first dimension chooses the lobe and is then stretched back to [0, 1).
        if (sample.x() < m_ks) {
            const Point2f reused(std::min(sample.x() / m_ks, OneMinusEpsilon), sample.y());
            const Vector3f wh = squareToBeckmann(reused, m_alpha);
            bRec.wo = 2.0f * wh.dot(bRec.wi) * wh - bRec.wi;
        } else {
            const Point2f reused(std::min((sample.x() - m_ks) / (1.0f - m_ks), OneMinusEpsilon), sample.y());
            bRec.wo = squareToCosineHemisphere(reused);
        }
        // A half-vector can mirror wi below the horizon: that sample is lost (pdf() excludes it).
        if (Frame::cosTheta(bRec.wo) <= 0.0f) return Color3f(0.0f);
        const float density = pdf(bRec);
        if (!(density > 0.0f)) return Color3f(0.0f);
        return eval(bRec) * Frame::cosTheta(bRec.wo) / density;
    }

    bool isDiffuse() const override { return true; }

    std::string toString() const override {
        return fmt::format("Microfacet[alpha={}, intIOR={}, extIOR={}, kd=({}, {}, {}), ks={}]", m_alpha, m_intIOR,
                           m_extIOR, m_kd[0], m_kd[1], m_kd[2], m_ks);
    }

private:
    static constexpr float OneMinusEpsilon = 0x1.fffffep-1f;

    /// Smith's masking for direction \p v and microfacet normal \p wh (Beckmann, rational fit).
    float smithG1(const Vector3f &v, const Vector3f &wh) const {
        const float cosV = Frame::cosTheta(v);
        // Back-facing microfacets are invisible from v.
        if (v.dot(wh) / cosV <= 0.0f) return 0.0f;
        const float tanV = std::sqrt(std::max(0.0f, 1.0f - cosV * cosV)) / cosV;
        if (tanV == 0.0f) return 1.0f;  // normal incidence: nothing is masked
        const float b = 1.0f / (m_alpha * tanV);
        if (b >= 1.6f) return 1.0f;
        return (3.535f * b + 2.181f * b * b) / (1.0f + 2.276f * b + 2.577f * b * b);
    }

    float m_alpha, m_intIOR, m_extIOR, m_ks;
    Color3f m_kd;
};

NORI_REGISTER_CLASS(Microfacet, "microfacet", EBSDF);

} // namespace nori
