/// \file wave_noise.h
/// \brief Smooth seeded "noise" as a sum of plane waves with random directions, phases and
/// octave-scaled frequencies: cheap, deterministic, and enough for terrain and rocks.
#pragma once

#include "gen_random.h"
#include <nori/common.h>
#include <cmath>
#include <vector>

namespace nori::gen {

/// \brief f(p) = sum_k a_k sin(f_k dir_k . p + phase_k), normalised to [-1, 1].
class WaveNoise {
public:
    /// \brief \p waves waves whose frequencies run geometrically from \p lowFrequency to
    /// \p highFrequency; amplitudes fall as 1 / frequency^roughness.
    WaveNoise(uint64_t seed, uint64_t stream, int waves, float lowFrequency, float highFrequency, float roughness = 1.0f) {
        GenRandom rng(seed, stream);
        float total = 0.0f;
        for (int k = 0; k < waves; ++k) {
            float t = waves > 1 ? float(k) / float(waves - 1) : 0.0f;
            float freq = lowFrequency * std::pow(highFrequency / lowFrequency, t);
            // A uniformly random direction on the sphere.
            float z = rng.range(-1.0f, 1.0f), phi = rng.range(0.0f, 2.0f * Pi);
            float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
            Wave w{Vector3f(r * std::cos(phi), r * std::sin(phi), z) * freq, rng.range(0.0f, 2.0f * Pi),
                   std::pow(freq / lowFrequency, -roughness)};
            total += w.amplitude;
            m_waves.push_back(w);
        }
        for (Wave &w : m_waves) w.amplitude /= total;
    }

    /// \brief Value in [-1, 1] at \p p.
    float operator()(const Vector3f &p) const {
        float sum = 0.0f;
        for (const Wave &w : m_waves) sum += w.amplitude * std::sin(w.k.dot(p) + w.phase);
        return sum;
    }
    /// \brief The same on the plane y = 0 (terrain).
    float operator()(float x, float z) const { return (*this)(Vector3f(x, 0.0f, z)); }

private:
    struct Wave {
        Vector3f k;  ///< direction times angular frequency
        float phase, amplitude;
    };
    std::vector<Wave> m_waves;
};

} // namespace nori::gen
