/// \file accuracy.h
/// \brief Compares a contender's answers with the Embree-robust reference.
#pragma once

#include <cstdint>
#include <vector>

namespace nori::bench {

/// \brief Disagreements of one ray set with the reference.
struct Accuracy {
    static constexpr double Tolerance = 1e-4;  ///< relative t difference counted as a mismatch

    uint64_t mismatches = 0;    ///< hit/miss (occluded) differs, or relative t error > Tolerance
    uint64_t hitMiss = 0;       ///< of which: hit/miss differs
    double maxRelTError = 0.0;  ///< over rays both report as hits

    /// \brief Compare \p answers with \p reference (same encoding as RaySet::reference).
    static Accuracy compare(const std::vector<float> &answers, const std::vector<float> &reference);
};

} // namespace nori::bench
