/// \file accuracy.cpp
/// \brief Compares a contender's answers with the Embree-robust reference (implementation).
#include "accuracy.h"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nori::bench {

Accuracy Accuracy::compare(const std::vector<float> &answers, const std::vector<float> &reference,
                           const std::vector<Ray3f> &rays) {
    if (answers.size() != reference.size() || rays.size() != reference.size())
        throw std::logic_error("Accuracy::compare: sizes differ");
    Accuracy a;
    for (size_t i = 0; i < answers.size(); ++i) {
        float t = answers[i], ref = reference[i];
        bool hit = std::isfinite(t), refHit = std::isfinite(ref);
        if (hit != refHit) {
            a.mismatchRays.push_back(uint32_t(i));
            ++a.mismatches;
            ++a.hitMiss;
            continue;
        }
        if (!hit || ref == t) continue;  // equal covers the shadow encoding (0 for occluded)
        double rel = std::abs(double(t) - double(ref)) / std::max(std::abs(double(ref)), 1e-30);
        a.maxRelTError = std::max(a.maxRelTError, rel);
        const Ray3f &ray = rays[i];
        Eigen::Vector3d o = ray.o.cast<double>(), d = ray.d.cast<double>();
        double scale = std::max(o.cwiseAbs().maxCoeff(), (o + double(ref) * d).cwiseAbs().maxCoeff());
        double apart = std::abs(double(t) - double(ref)) * d.norm();
        if (apart > std::max(Tolerance * std::abs(double(ref)) * d.norm(), ScaleTolerance * scale)) {
            a.mismatchRays.push_back(uint32_t(i));
            ++a.mismatches;
        }
    }
    return a;
}

} // namespace nori::bench
