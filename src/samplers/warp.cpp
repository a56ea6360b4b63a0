/// \file warp.cpp
/// \brief The warping functions of warp.h (inverse-CDF constructions, each with its density).
#include <nori/warp.h>

namespace nori {

namespace {
/// Inverse CDF of the 1D tent 1 - |t| on [-1, 1]: each half is a triangle of mass 1/2.
float tentInverse(float u) {
    return u < 0.5f ? std::sqrt(2.0f * u) - 1.0f : 1.0f - std::sqrt(2.0f - 2.0f * u);
}

/// Unit vector with height \p z at azimuth \p phi.
Vector3f fromHeightAndAngle(float z, float phi) {
    float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return Vector3f(r * std::cos(phi), r * std::sin(phi), z);
}
} // namespace

Point2f squareToUniformSquare(const Point2f &sample) { return sample; }

float squareToUniformSquarePdf(const Point2f &p) {
    return (p.array() >= 0.0f).all() && (p.array() <= 1.0f).all() ? 1.0f : 0.0f;
}

Point2f squareToTent(const Point2f &sample) { return Point2f(tentInverse(sample.x()), tentInverse(sample.y())); }

float squareToTentPdf(const Point2f &p) {
    return std::max(0.0f, 1.0f - std::abs(p.x())) * std::max(0.0f, 1.0f - std::abs(p.y()));
}

Point2f squareToUniformDisk(const Point2f &sample) {
    // The area inside radius r grows as r^2, so r = sqrt(u) makes the area uniform.
    float r = std::sqrt(sample.x());
    float phi = 2.0f * Pi * sample.y();
    return Point2f(r * std::cos(phi), r * std::sin(phi));
}

float squareToUniformDiskPdf(const Point2f &p) { return p.squaredNorm() <= 1.0f ? InvPi : 0.0f; }

Point2f squareToUniformTriangle(const Point2f &sample) {
    // Osada et al. 2002: b0 = 1 - sqrt(u) makes the strips parallel to the far edge uniform by
    // area; v splits each strip uniformly.
    float s = std::sqrt(sample.x());
    return Point2f(sample.y() * s, 1.0f - s);
}

float squareToUniformTrianglePdf(const Point2f &p) {
    return p.x() >= 0.0f && p.y() >= 0.0f && p.x() + p.y() <= 1.0f ? 2.0f : 0.0f;
}

Vector3f squareToUniformSphere(const Point2f &sample) {
    // Archimedes: the area of a spherical zone is proportional to its height, so z is uniform.
    return fromHeightAndAngle(1.0f - 2.0f * sample.x(), 2.0f * Pi * sample.y());
}

float squareToUniformSpherePdf(const Vector3f &) { return InvFourPi; }

Vector3f squareToUniformHemisphere(const Point2f &sample) {
    return fromHeightAndAngle(sample.x(), 2.0f * Pi * sample.y());
}

float squareToUniformHemispherePdf(const Vector3f &v) { return v.z() >= 0.0f ? InvTwoPi : 0.0f; }

Vector3f squareToCosineHemisphere(const Point2f &sample) {
    Point2f d = squareToUniformDisk(sample);
    return Vector3f(d.x(), d.y(), std::sqrt(std::max(0.0f, 1.0f - sample.x())));
}

float squareToCosineHemispherePdf(const Vector3f &v) { return v.z() > 0.0f ? v.z() * InvPi : 0.0f; }

Vector3f squareToBeckmann(const Point2f &sample, float alpha) {
    // The marginal CDF in theta is 1 - exp(-tan^2(theta)/alpha^2); invert it for 1 - u (log1p
    // keeps precision for small u). Azimuth is uniform.
    // sin(theta) comes from tan^2 directly: sqrt(1 - cos^2) would lose the small angles of a
    // smooth surface to rounding.
    float tan2Theta = -alpha * alpha * std::log1p(-sample.y());
    float cosTheta = 1.0f / std::sqrt(1.0f + tan2Theta);
    float sinTheta = std::sqrt(tan2Theta) * cosTheta;
    float phi = 2.0f * Pi * sample.x();
    return Vector3f(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
}

float squareToBeckmannPdf(const Vector3f &m, float alpha) {
    float cosTheta = m.z();
    if (cosTheta <= 0.0f) return 0.0f;
    float cos2Theta = cosTheta * cosTheta;
    float tan2Theta = std::max(0.0f, 1.0f - cos2Theta) / cos2Theta;
    float alpha2 = alpha * alpha;
    return std::exp(-tan2Theta / alpha2) / (Pi * alpha2 * cos2Theta * cosTheta);
}

} // namespace nori
