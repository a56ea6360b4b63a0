/// \file hypothesis.h
/// \brief Hypothesis tests used by Nori's test harnesses: Pearson's chi^2 goodness of fit with
/// pooling of sparse cells, the one-sample Student t-test, and the Sidak correction.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace nori {

/// \brief Outcome of one hypothesis test and the lines that explain it.
struct HypothesisResult {
    bool accepted = false;  ///< the null hypothesis survived
    double pValue = 0.0;    ///< NaN when the test could not be carried out
    std::string report;     ///< newline-terminated lines for the user
};

/// \brief Per-test level that keeps the family-wise error rate at \p alpha over \p testCount
/// independent tests: 1 - (1 - alpha)^(1/testCount) (Sidak 1967).
double sidakCorrection(double alpha, int testCount);

/// \brief Pearson's chi^2 test of \p observed cell counts against \p expected ones. Cells
/// expecting fewer than \p minExpFrequency samples are pooled into one cell (in increasing order
/// of expectation, until the pool itself reaches \p minExpFrequency); a cell expecting zero must
/// not hold more than \p sampleCount * 1e-5 samples. The null hypothesis is rejected when the
/// p-value is below \p significanceLevel or not a number.
HypothesisResult chi2Test(const std::vector<double> &observed, const std::vector<double> &expected,
                          double sampleCount, double minExpFrequency, double significanceLevel);

/// \brief Two-sided one-sample t-test of H0: the mean is \p reference, from \p sampleCount
/// samples with the given mean and unbiased variance. As Nori, the variance is floored at 1e-5
/// (a noiseless estimator equal to its reference is accepted, one off by any amount rejected).
HypothesisResult tTest(double sampleMean, double sampleVariance, uint64_t sampleCount, double reference,
                       double significanceLevel);

} // namespace nori
