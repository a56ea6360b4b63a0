/// \file gen_random.h
/// \brief Seeded random numbers for the generators: the same on every platform (pcg32 and
/// plain arithmetic only; no std:: distributions, whose output is implementation-defined).
#pragma once

#include <nori/common.h>
#include <pcg_random.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace nori::gen {

/// \brief pcg32 with the few draws the generators need.
class GenRandom {
public:
    /// \brief \p stream separates the independent sequences of one scene (layout, sizes, ...).
    explicit GenRandom(uint64_t seed, uint64_t stream = 0) : m_rng(seed, stream) {}
    /// \brief Uniform in [0, 1).
    float uniform() { return float(m_rng() >> 8) * 0x1p-24f; }
    /// \brief Uniform in [lo, hi).
    float range(float lo, float hi) { return lo + (hi - lo) * uniform(); }
    /// \brief Uniform integer in [0, n).
    uint32_t below(uint32_t n) { return m_rng(n); }
    /// \brief Uniformly random direction (Archimedes: z uniform in [-1, 1], angle uniform).
    Vector3f direction() {
        float z = range(-1.0f, 1.0f), phi = range(0.0f, 2.0f * Pi);
        float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return Vector3f(r * std::cos(phi), r * std::sin(phi), z);
    }
    /// \brief Log-uniform in [lo, hi): as many draws in every decade.
    float logRange(float lo, float hi) { return lo * std::pow(hi / lo, uniform()); }

private:
    pcg32 m_rng;
};

} // namespace nori::gen
