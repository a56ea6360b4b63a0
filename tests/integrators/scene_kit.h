/// \file scene_kit.h
/// \brief Small scenes written on the fly for the integrator tests: OBJ quads and boxes, a scene
/// loaded from XML text, and Nori's scene estimator (mean luminance of Li over random camera rays).
#pragma once

#include <nori/parser.h>
#include <nori/running_statistics.h>
#include <nori/sampler.h>
#include <nori/scene.h>
#include <temp_dir.h>
#include <array>
#include <cmath>
#include <sstream>
#include <vector>

namespace nori::kit {

/// \brief OBJ text of quads (four corners each, split into (0,1,2) and (0,2,3)); the winding
/// gives the normal (p1 - p0) x (p2 - p0).
inline std::string quadsObj(const std::vector<std::array<Point3f, 4>> &quads) {
    std::ostringstream s;
    s.precision(9);
    for (const auto &q : quads)
        for (const Point3f &p : q) s << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    for (size_t i = 0; i < quads.size(); ++i) {
        size_t b = 4 * i + 1;
        s << "f " << b << ' ' << b + 1 << ' ' << b + 2 << '\n' << "f " << b << ' ' << b + 2 << ' ' << b + 3 << '\n';
    }
    return s.str();
}

/// \brief A horizontal square of side \p side at height \p y centred on (cx, cz), normal +y.
inline std::array<Point3f, 4> squareY(float cx, float y, float cz, float side) {
    float h = 0.5f * side;
    return {Point3f(cx - h, y, cz - h), Point3f(cx - h, y, cz + h), Point3f(cx + h, y, cz + h), Point3f(cx + h, y, cz - h)};
}

/// \brief The six faces of the axis-aligned cube [lo, hi]^3 shifted by \p c, normals pointing inwards.
inline std::vector<std::array<Point3f, 4>> cubeInward(const Point3f &c, float lo, float hi) {
    auto P = [&](float x, float y, float z) { return Point3f(c.x() + x, c.y() + y, c.z() + z); };
    return {
        {P(lo, lo, lo), P(lo, lo, hi), P(hi, lo, hi), P(hi, lo, lo)},  // floor, normal +y
        {P(lo, hi, lo), P(hi, hi, lo), P(hi, hi, hi), P(lo, hi, hi)},  // ceiling, -y
        {P(lo, lo, lo), P(lo, hi, lo), P(lo, hi, hi), P(lo, lo, hi)},  // x = lo, +x
        {P(hi, lo, lo), P(hi, lo, hi), P(hi, hi, hi), P(hi, hi, lo)},  // x = hi, -x
        {P(lo, lo, lo), P(hi, lo, lo), P(hi, hi, lo), P(lo, hi, lo)},  // z = lo, +z
        {P(lo, lo, hi), P(lo, hi, hi), P(hi, hi, hi), P(hi, lo, hi)},  // z = hi, -z
    };
}

/// \brief "x, y, z" for XML attributes.
inline std::string xyz(const Point3f &p) {
    std::ostringstream s;
    s.precision(9);
    s << p.x() << ", " << p.y() << ", " << p.z();
    return s.str();
}

/// \brief Load a scene written to \p dir as \p name.
inline std::unique_ptr<Scene> loadSceneText(const TempDir &dir, const std::string &name, const std::string &xml) {
    return loadScene(dir.write(name, xml));
}

/// \brief Running mean and variance of the scene estimator's samples.
using Estimate = RunningStatistics;

/// \brief Nori's scene estimator: \p count camera rays through uniformly random film positions,
/// luminance of weight * Li. \p visit (optional) sees every ray and value.
template <typename Visit>
Estimate estimateScene(const Scene &scene, size_t count, uint64_t seed, Visit visit) {
    std::unique_ptr<Sampler> sampler = scene.sampler().clone();
    sampler->prepare(seed);
    const Camera &camera = scene.camera();
    Vector2i size = camera.outputSize();
    Estimate e;
    for (size_t i = 0; i < count; ++i) {
        Point2f pixel = sampler->next2D().cwiseProduct(size.cast<float>());
        Ray3f ray;
        Color3f weight = camera.sampleRay(ray, pixel, sampler->next2D());
        Color3f value = weight * scene.integrator().Li(scene, *sampler, ray);
        visit(ray, value);
        e.add(luminance(value));
    }
    return e;
}

inline Estimate estimateScene(const Scene &scene, size_t count, uint64_t seed) {
    return estimateScene(scene, count, seed, [](const Ray3f &, const Color3f &) {});
}

} // namespace nori::kit
