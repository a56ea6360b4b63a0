/// \file running_statistics.h
/// \brief Mean and variance of a stream of samples in one pass, for the statistical tests.
#pragma once

#include <cmath>
#include <cstdint>

namespace nori {

/// \brief Welford's update (Welford 1962): stable where the textbook sum of squares cancels,
/// which matters for t-tests over millions of nearly equal radiance samples.
class RunningStatistics {
public:
    void add(double x) {
        ++m_count;
        double delta = x - m_mean;
        m_mean += delta / double(m_count);
        m_m2 += delta * (x - m_mean);
    }
    uint64_t count() const { return m_count; }
    double mean() const { return m_mean; }
    /// \brief Unbiased sample variance (0 below two samples).
    double variance() const { return m_count > 1 ? m_m2 / double(m_count - 1) : 0.0; }
    /// \brief Standard error of the mean.
    double standardError() const { return m_count > 0 ? std::sqrt(variance() / double(m_count)) : 0.0; }

private:
    uint64_t m_count = 0;
    double m_mean = 0.0, m_m2 = 0.0;
};

} // namespace nori
