/// \file color.h
/// \brief Linear RGB colour.
#pragma once

#include <nori/common.h>

namespace nori {

/// \brief Linear RGB triple; arithmetic is component-wise (Eigen array).
using Color3f = Eigen::Array3f;

/// \brief sRGB transfer function of one linear component (IEC 61966-2-1).
inline float linearToSRGB(float value) {
    if (value <= 0.0031308f) return 12.92f * value;
    return 1.055f * std::pow(value, 1.0f / 2.4f) - 0.055f;
}

/// \brief Luminance (Rec. 709 weights).
inline float luminance(const Color3f &c) { return 0.212671f * c[0] + 0.715160f * c[1] + 0.072169f * c[2]; }

/// \brief True when every component is finite.
inline bool isFinite(const Color3f &c) { return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]); }

} // namespace nori
