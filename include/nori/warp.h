/// \file warp.h
/// \brief Warping of uniform samples to directions.
#pragma once

#include <nori/common.h>

namespace nori {

/// \brief Cosine-weighted direction about +z (Malley's method: a uniform disk sample lifted
/// to the hemisphere). Its density is cos(theta) / pi.
inline Vector3f squareToCosineHemisphere(const Point2f &sample) {
    float r = std::sqrt(sample.x());
    float phi = 2.0f * Pi * sample.y();
    return Vector3f(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - sample.x())));
}

} // namespace nori
