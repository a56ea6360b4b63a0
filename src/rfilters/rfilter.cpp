/// \file rfilter.cpp
/// \brief Reconstruction filter plugins: gaussian, box, tent and mitchell.
#include <nori/rfilter.h>
#include <cmath>

namespace nori {

namespace {

/// Read an optional positive, finite float property, rejecting anything else with its location.
float positiveProperty(const PropertyList &props, const std::string &name, float defaultValue) {
    float value = props.getFloat(name, defaultValue);
    if (!std::isfinite(value) || value <= 0.0f)
        props.fail(name, fmt::format("'{}' must be a positive finite number (got {})", name, value));
    return value;
}

/// A filter radius: positive, and at most MaxRadius pixels. A wider filter does not sharpen
/// anything; it only makes every sample touch (2r)^2 pixels (2000 took 14 s on 16x16 pixels).
constexpr float MaxRadius = 32.0f;
float radiusProperty(const PropertyList &props, float defaultValue) {
    float value = positiveProperty(props, "radius", defaultValue);
    if (value > MaxRadius)
        props.fail("radius", fmt::format("filter radius must be at most {} pixels (got {})", MaxRadius, value));
    return value;
}

/// Read an optional finite float property.
float finiteProperty(const PropertyList &props, const std::string &name, float defaultValue) {
    float value = props.getFloat(name, defaultValue);
    if (!std::isfinite(value)) props.fail(name, fmt::format("'{}' must be a finite number (got {})", name, value));
    return value;
}

/// Truncated Gaussian, shifted down so that it reaches exactly zero at the radius
/// (otherwise the truncation leaves a visible step at the edge of the support).
class GaussianFilter : public ReconstructionFilter {
public:
    explicit GaussianFilter(const PropertyList &props) {
        m_radius = radiusProperty(props, 2.0f);
        m_stddev = positiveProperty(props, "stddev", 0.5f);
        m_alpha = 1.0f / (2.0f * m_stddev * m_stddev);
        m_floor = std::exp(-m_alpha * m_radius * m_radius);
    }

    float eval(float x) const override {
        if (!(std::abs(x) <= m_radius)) return 0.0f;
        return std::max(0.0f, std::exp(-m_alpha * x * x) - m_floor);
    }

    std::string toString() const override {
        return fmt::format("GaussianFilter[radius={}, stddev={}]", m_radius, m_stddev);
    }

private:
    float m_stddev, m_alpha, m_floor;
};

/// Box of width one pixel: every sample contributes to exactly one pixel.
class BoxFilter : public ReconstructionFilter {
public:
    explicit BoxFilter(const PropertyList &) { m_radius = 0.5f; }

    float eval(float x) const override { return std::abs(x) <= m_radius ? 1.0f : 0.0f; }

    std::string toString() const override { return "BoxFilter[radius=0.5]"; }
};

/// Tent (triangle): linear fall-off from 1 at the centre to 0 at the radius.
class TentFilter : public ReconstructionFilter {
public:
    explicit TentFilter(const PropertyList &props) { m_radius = radiusProperty(props, 1.0f); }

    float eval(float x) const override { return std::max(0.0f, 1.0f - std::abs(x) / m_radius); }

    std::string toString() const override { return fmt::format("TentFilter[radius={}]", m_radius); }
};

/// Mitchell & Netravali 1988, "Reconstruction Filters in Computer Graphics", SIGGRAPH '88, eq. (8):
///   k(x) = 1/6 * { (12 - 9B - 6C)|x|^3 + (-18 + 12B + 6C)|x|^2 + (6 - 2B)                  if |x| < 1
///                { (-B - 6C)|x|^3 + (6B + 30C)|x|^2 + (-12B - 48C)|x| + (8B + 24C)        if 1 <= |x| < 2
///                { 0                                                                       otherwise
/// The kernel is defined on [-2, 2]; it is stretched to [-radius, radius] by evaluating k(2x / radius).
/// At the default radius 2 it integrates to one; B = C = 1/3 is the authors' recommended trade-off.
class MitchellFilter : public ReconstructionFilter {
public:
    explicit MitchellFilter(const PropertyList &props) {
        m_radius = radiusProperty(props, 2.0f);
        m_B = finiteProperty(props, "B", 1.0f / 3.0f);
        m_C = finiteProperty(props, "C", 1.0f / 3.0f);
    }

    float eval(float x) const override {
        float t = std::abs(2.0f * x / m_radius);
        float t2 = t * t, t3 = t2 * t;
        float B = m_B, C = m_C;
        if (t < 1.0f)
            return ((12.0f - 9.0f * B - 6.0f * C) * t3 + (-18.0f + 12.0f * B + 6.0f * C) * t2 + (6.0f - 2.0f * B)) *
                   (1.0f / 6.0f);
        if (t < 2.0f)
            return ((-B - 6.0f * C) * t3 + (6.0f * B + 30.0f * C) * t2 + (-12.0f * B - 48.0f * C) * t +
                    (8.0f * B + 24.0f * C)) *
                   (1.0f / 6.0f);
        return 0.0f;
    }

    std::string toString() const override {
        return fmt::format("MitchellFilter[radius={}, B={}, C={}]", m_radius, m_B, m_C);
    }

private:
    float m_B, m_C;
};

} // namespace

NORI_REGISTER_CLASS(GaussianFilter, "gaussian", EReconstructionFilter);
NORI_REGISTER_CLASS(BoxFilter, "box", EReconstructionFilter);
NORI_REGISTER_CLASS(TentFilter, "tent", EReconstructionFilter);
NORI_REGISTER_CLASS(MitchellFilter, "mitchell", EReconstructionFilter);

} // namespace nori
