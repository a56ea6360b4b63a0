/// \file warp_catalog.h
/// \brief The warping functions nori-warptest knows by name, and the chi^2 test of a warp's
/// samples against a density (NORI-SPEC 5.2).
#pragma once

#include "hypothesis.h"
#include <nori/common.h>
#include <functional>
#include <memory>
#include <optional>

namespace nori {

/// \brief A named warp: how it turns a uniform sample into a point and the density it claims.
/// Planar warps produce (x, y, 0) in the rectangle \c bounds; spherical ones unit vectors.
struct NamedWarp {
    std::string name;
    std::string parameters;  ///< for reports, e.g. "alpha = 0.1"
    bool spherical = false;
    Eigen::Vector4d bounds{0, 0, 1, 1};  ///< planar domain: x0, y0, x1, y1
    /// Warped point, or nothing when the sample is lost (a BSDF sample of weight zero).
    std::function<std::optional<Vector3f>(const Point2f &)> sample;
    std::function<double(const Vector3f &)> pdf;
};

/// \brief The names makeWarp() accepts, in a fixed order.
const std::vector<std::string> &warpNames();

/// \brief The warp called \p name with its numeric \p parameters (beckmann: alpha;
/// microfacet_brdf: alpha and optionally a grey kd). \p incidentDeg is the microfacet BRDF's
/// incident angle. Throws NoriException for an unknown name or bad parameters.
NamedWarp makeWarp(const std::string &name, const std::vector<float> &parameters, float incidentDeg = 0.0f);

/// \brief Histogram of \p samplesPerCell times the cell count samples of \p sampled (51 x 51
/// cells over a planar domain; 50 (z) x 100 (phi) over the sphere, so that the horizon is a cell
/// edge) against the integral of \p reference's pdf over each cell; chi^2 test with cells pooled
/// below 5 expected samples, significance level 0.01.
HypothesisResult testWarp(const NamedWarp &sampled, const NamedWarp &reference, int samplesPerCell = 1000);

} // namespace nori
