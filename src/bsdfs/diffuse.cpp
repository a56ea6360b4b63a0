/// Lambertian BSDF (Nori's `diffuse`).
#include <nori/bsdf.h>
#include <nori/frame.h>

namespace nori {

class Diffuse : public BSDF {
public:
    explicit Diffuse(const PropertyList &props) {
        m_albedo = props.getColor("albedo", Color3f(0.5f));
        if (!(m_albedo >= 0.0f).all()) props.fail("albedo", "albedo must not be negative");
    }

    Color3f eval(const Vector3f &wi, const Vector3f &wo) const override {
        if (Frame::cosTheta(wi) <= 0.0f || Frame::cosTheta(wo) <= 0.0f) return Color3f(0.0f);
        return m_albedo * InvPi;
    }

    std::string toString() const override {
        return fmt::format("Diffuse[albedo=({}, {}, {})]", m_albedo[0], m_albedo[1], m_albedo[2]);
    }

private:
    Color3f m_albedo;
};

NORI_REGISTER_CLASS(Diffuse, "diffuse", EBSDF);

} // namespace nori
