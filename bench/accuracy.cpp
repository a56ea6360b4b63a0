/// \file accuracy.cpp
/// \brief Compares a contender's answers with the Embree-robust reference (implementation).
#include "accuracy.h"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nori::bench {

Accuracy Accuracy::compare(const std::vector<float> &answers, const std::vector<float> &reference) {
    if (answers.size() != reference.size()) throw std::logic_error("Accuracy::compare: sizes differ");
    Accuracy a;
    for (size_t i = 0; i < answers.size(); ++i) {
        float t = answers[i], ref = reference[i];
        bool hit = std::isfinite(t), refHit = std::isfinite(ref);
        if (hit != refHit) {
            ++a.mismatches;
            ++a.hitMiss;
            continue;
        }
        if (!hit) continue;
        double rel = std::abs(double(t) - double(ref)) / std::max(std::abs(double(ref)), 1e-30);
        if (ref == t) rel = 0.0;  // covers the shadow encoding (0 for occluded)
        a.maxRelTError = std::max(a.maxRelTError, rel);
        if (rel > Tolerance) ++a.mismatches;
    }
    return a;
}

} // namespace nori::bench
