/// \file diffuse.cpp
/// \brief Lambertian BSDF (Nori's `diffuse`), importance-sampled with cosine-weighted directions.
#include <nori/bsdf.h>
#include <nori/frame.h>
#include <nori/warp.h>

namespace nori {

/// \brief Ideal diffuse reflection: f = albedo / pi on the side the shading normal points to.
class Diffuse : public BSDF {
public:
    explicit Diffuse(const PropertyList &props) {
        m_albedo = props.getColor("albedo", Color3f(0.5f));
        if (!(m_albedo >= 0.0f).all()) props.fail("albedo", "albedo must not be negative");
    }

    Color3f eval(const BSDFQueryRecord &bRec) const override {
        if (bRec.measure != EMeasure::SolidAngle || Frame::cosTheta(bRec.wi) <= 0.0f ||
            Frame::cosTheta(bRec.wo) <= 0.0f)
            return Color3f(0.0f);
        return m_albedo * InvPi;
    }

    float pdf(const BSDFQueryRecord &bRec) const override {
        if (bRec.measure != EMeasure::SolidAngle || Frame::cosTheta(bRec.wi) <= 0.0f ||
            Frame::cosTheta(bRec.wo) <= 0.0f)
            return 0.0f;
        return InvPi * Frame::cosTheta(bRec.wo);
    }

    Color3f sample(BSDFQueryRecord &bRec, const Point2f &sample) const override {
        if (Frame::cosTheta(bRec.wi) <= 0.0f) return Color3f(0.0f);
        bRec.measure = EMeasure::SolidAngle;
        bRec.wo = squareToCosineHemisphere(sample);
        bRec.eta = 1.0f;
        // eval * cos / pdf = (albedo / pi) * cos / (cos / pi): the cosine and 1/pi cancel.
        return Frame::cosTheta(bRec.wo) > 0.0f ? m_albedo : Color3f(0.0f);
    }

    bool isDiffuse() const override { return true; }

    std::string toString() const override {
        return fmt::format("Diffuse[albedo=({}, {}, {})]", m_albedo[0], m_albedo[1], m_albedo[2]);
    }

private:
    Color3f m_albedo;
};

NORI_REGISTER_CLASS(Diffuse, "diffuse", EBSDF);

} // namespace nori
