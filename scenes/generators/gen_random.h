/// \file gen_random.h
/// \brief Seeded random numbers for the generators: the same on every platform (pcg32 and
/// plain arithmetic only; no std:: distributions, whose output is implementation-defined).
#pragma once

#include <pcg_random.hpp>
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

private:
    pcg32 m_rng;
};

} // namespace nori::gen
