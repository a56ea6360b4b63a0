/// \file dpdf.h
/// \brief Discrete probability distribution over n entries, sampled by inverting its CDF.
#pragma once

#include <nori/common.h>
#include <vector>

namespace nori {

/// \brief Weights appended one by one, then normalised; sampling is a binary search in the CDF.
class DiscretePDF {
public:
    /// \brief Room for \p n entries.
    void reserve(size_t n) { m_cdf.reserve(n + 1); }
    /// \brief Remove every entry.
    void clear();
    /// \brief Add an entry of (unnormalised, non-negative) weight \p weight.
    void append(float weight);
    /// \brief Normalise the weights to probabilities; returns their sum (0: the distribution is empty).
    float normalize();

    size_t size() const { return m_cdf.size() - 1; }
    /// \brief Sum of the weights before normalize().
    float sum() const { return m_sum; }
    /// \brief Probability of entry \p i (after normalize()).
    float operator[](size_t i) const { return float(m_cdf[i + 1] - m_cdf[i]); }

    /// \brief The entry whose CDF interval holds \p u in [0, 1).
    size_t sample(float u) const;
    /// \brief sample(), and rescale \p u to a fresh uniform sample in [0, 1) from its position
    /// inside the chosen interval (one random number serves for the choice and what follows).
    size_t sampleReuse(float &u) const;

private:
    std::vector<double> m_cdf{0.0};  ///< running sums; double so that a million entries stay exact enough
    float m_sum = 0.0f;
};

} // namespace nori
