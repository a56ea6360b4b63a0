/// \file warp_catalog.cpp
/// \brief Named warps for nori-warptest and their chi^2 test.
#include "warp_catalog.h"
#include "simpson.h"
#include <nori/bsdf.h>
#include <nori/warp.h>
#include <algorithm>
#include <atomic>
#include <fmt/ranges.h>
#include <pcg_random.hpp>
#include <tbb/parallel_for.h>

namespace nori {

namespace {

/// A planar warp of a square sample.
NamedWarp planar(const char *name, Eigen::Vector4d bounds, Point2f (*warp)(const Point2f &),
                 float (*pdf)(const Point2f &)) {
    NamedWarp w;
    w.name = name;
    w.bounds = bounds;
    w.sample = [warp](const Point2f &u) -> std::optional<Vector3f> {
        Point2f p = warp(u);
        return Vector3f(p.x(), p.y(), 0.0f);
    };
    w.pdf = [pdf](const Vector3f &p) { return double(pdf(Point2f(p.x(), p.y()))); };
    return w;
}

NamedWarp spherical(const char *name, Vector3f (*warp)(const Point2f &), float (*pdf)(const Vector3f &)) {
    NamedWarp w;
    w.name = name;
    w.spherical = true;
    w.sample = [warp](const Point2f &u) -> std::optional<Vector3f> { return warp(u); };
    w.pdf = [pdf](const Vector3f &v) { return double(pdf(v)); };
    return w;
}

/// The microfacet BSDF's sampling of outgoing directions for one incident direction.
NamedWarp microfacetBRDF(float alpha, float kd, float incidentDeg) {
    PropertyList props;
    props.setLocation("nori-warptest");
    props.setFloat("alpha", alpha, "nori-warptest ALPHA");
    props.setColor("kd", Color3f(kd), "nori-warptest KD");
    std::shared_ptr<BSDF> bsdf(static_cast<BSDF *>(
        NoriObjectFactory::createInstance(NoriObject::EBSDF, "microfacet", props).release()));
    const float theta = degToRad(incidentDeg);
    const Vector3f wi(std::sin(theta), 0.0f, std::max(std::cos(theta), 1e-4f));
    NamedWarp w;
    w.name = "microfacet_brdf";
    w.parameters = fmt::format("alpha = {}, kd = {}, incident angle = {} deg", alpha, kd, incidentDeg);
    w.spherical = true;
    w.sample = [bsdf, wi](const Point2f &u) -> std::optional<Vector3f> {
        BSDFQueryRecord rec(wi.normalized());
        if ((bsdf->sample(rec, u) == 0.0f).all()) return std::nullopt;
        return rec.wo;
    };
    w.pdf = [bsdf, wi](const Vector3f &wo) {
        return double(bsdf->pdf(BSDFQueryRecord(wi.normalized(), wo, EMeasure::SolidAngle)));
    };
    return w;
}

float parameter(const std::string &name, const std::vector<float> &parameters, size_t index, const char *what) {
    if (parameters.size() <= index) throw NoriException("warp '{}' needs the parameter {}", name, what);
    return parameters[index];
}

} // namespace

const std::vector<std::string> &warpNames() {
    static const std::vector<std::string> names = {"square", "tent", "disk", "uniform_triangle", "uniform_sphere",
                                                   "uniform_hemisphere", "cosine_hemisphere", "beckmann",
                                                   "microfacet_brdf"};
    return names;
}

NamedWarp makeWarp(const std::string &name, const std::vector<float> &parameters, float incidentDeg) {
    const size_t allowed = name == "beckmann" ? 1 : name == "microfacet_brdf" ? 2 : 0;
    if (std::find(warpNames().begin(), warpNames().end(), name) == warpNames().end())
        throw NoriException("unknown warp '{}' (known: {})", name.substr(0, 60), fmt::join(warpNames(), ", "));
    if (parameters.size() > allowed)
        throw NoriException("warp '{}' takes {} parameter{}, got {}", name, allowed, allowed == 1 ? "" : "s",
                            parameters.size());
    const Eigen::Vector4d unit(0, 0, 1, 1), centred(-1, -1, 1, 1);
    if (name == "square") return planar("square", unit, squareToUniformSquare, squareToUniformSquarePdf);
    if (name == "tent") return planar("tent", centred, squareToTent, squareToTentPdf);
    if (name == "disk") return planar("disk", centred, squareToUniformDisk, squareToUniformDiskPdf);
    if (name == "uniform_triangle")
        return planar("uniform_triangle", unit, squareToUniformTriangle, squareToUniformTrianglePdf);
    if (name == "uniform_sphere") return spherical("uniform_sphere", squareToUniformSphere, squareToUniformSpherePdf);
    if (name == "uniform_hemisphere")
        return spherical("uniform_hemisphere", squareToUniformHemisphere, squareToUniformHemispherePdf);
    if (name == "cosine_hemisphere")
        return spherical("cosine_hemisphere", squareToCosineHemisphere, squareToCosineHemispherePdf);
    const float alpha = parameter(name, parameters, 0, "ALPHA");
    if (!(alpha > 0.0f) || !std::isfinite(alpha)) throw NoriException("alpha must be positive, got {}", alpha);
    if (name == "beckmann") {
        NamedWarp w;
        w.name = "beckmann";
        w.parameters = fmt::format("alpha = {}", alpha);
        w.spherical = true;
        w.sample = [alpha](const Point2f &u) -> std::optional<Vector3f> { return squareToBeckmann(u, alpha); };
        w.pdf = [alpha](const Vector3f &m) { return double(squareToBeckmannPdf(m, alpha)); };
        return w;
    }
    const float kd = parameters.size() > 1 ? parameters[1] : 0.5f;
    if (!(kd >= 0.0f && kd <= 1.0f)) throw NoriException("kd must be in [0, 1], got {}", kd);
    return microfacetBRDF(alpha, kd, incidentDeg);
}

HypothesisResult testWarp(const NamedWarp &sampled, const NamedWarp &reference, int samplesPerCell) {
    // Grid over the domain: (x, y) for planar warps, (z, phi) for spherical ones.
    const int nx = sampled.spherical ? 50 : 51, ny = sampled.spherical ? 100 : 51;
    const Eigen::Vector4d box = sampled.spherical ? Eigen::Vector4d(-1, 0, 1, 2 * M_PI) : sampled.bounds;
    const uint64_t sampleCount = uint64_t(samplesPerCell) * nx * ny;
    auto edge = [&](int axis, int k) {
        const int n = axis == 0 ? nx : ny;
        return box[axis] + (box[axis + 2] - box[axis]) * double(k) / n;  // exact at k = 0, n (and z = 0)
    };
    auto cellOf = [&](const Vector3f &p) -> long {
        double a = p.x(), b = p.y();
        if (sampled.spherical) {
            a = p.z();
            b = std::atan2(p.y(), p.x());
            if (b < 0.0) b += 2 * M_PI;
        }
        // Planar points outside the (closed) domain are an error of the warp: no cell expects
        // them. Directions are binned by z and phi, which rounding cannot push far out.
        if (!sampled.spherical && !(a >= box[0] && a <= box[2] && b >= box[1] && b <= box[3])) return -1;
        const int i = clamp(int(std::floor((a - box[0]) / (box[2] - box[0]) * nx)), 0, nx - 1);
        const int j = clamp(int(std::floor((b - box[1]) / (box[3] - box[1]) * ny)), 0, ny - 1);
        return long(i) * ny + j;
    };

    std::vector<double> observed(size_t(nx) * ny, 0.0);
    uint64_t outside = 0;
    pcg32 rng;
    for (uint64_t s = 0; s < sampleCount; ++s) {
        const float u = float(rng() >> 8) * 0x1p-24f;
        const std::optional<Vector3f> p = sampled.sample(Point2f(u, float(rng() >> 8) * 0x1p-24f));
        if (!p) continue;
        const long cell = cellOf(*p);
        if (cell < 0) ++outside;
        else observed[size_t(cell)] += 1.0;
    }
    auto density = [&](double a, double b) {
        if (!sampled.spherical) return reference.pdf(Vector3f(float(a), float(b), 0.0f));
        const double r = std::sqrt(std::max(0.0, 1.0 - a * a));
        return reference.pdf(Vector3f(float(r * std::cos(b)), float(r * std::sin(b)), float(a)));
    };
    std::vector<double> expected(observed.size());
    std::atomic<bool> negative{false};
    tbb::parallel_for(size_t(0), expected.size(), [&](size_t cell) {
        const int i = int(cell / ny), j = int(cell % ny);
        expected[cell] = double(sampleCount) * integrateCell(density, edge(0, i), edge(1, j), edge(0, i + 1),
                                                                 edge(1, j + 1));
        if (expected[cell] < 0.0) negative = true;
    });
    HypothesisResult result;
    if (negative) {
        result.report = "The pdf returned negative values. Rejecting the null hypothesis!\n";
    } else if (outside > 0) {
        result.report = fmt::format("{} samples fell outside the warp's domain. Rejecting the null hypothesis!\n",
                                    outside);
    } else {
        result = chi2Test(observed, expected, double(sampleCount), 5.0, 0.01);
    }
    result.report = fmt::format("Histogram of {} samples in {}x{} cells, expected counts from the pdf of {}{}\n",
                                sampleCount, nx, ny, reference.name,
                                reference.parameters.empty() ? "" : " (" + reference.parameters + ")") +
                    result.report;
    return result;
}

} // namespace nori
