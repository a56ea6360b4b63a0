/// \file hypothesis.cpp
/// \brief chi^2 and t-tests on the distributions of Boost.Math.
#include "hypothesis.h"
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <fmt/format.h>
#include <numeric>

namespace nori {

namespace {
std::string verdictLine(bool accepted, double pValue, double level) {
    return fmt::format("{} the null hypothesis (p-value = {:.6g}, significance level = {:.6g})\n",
                       accepted ? "Accepted" : "***** Rejected *****", pValue, level);
}

HypothesisResult rejected(std::string report) {
    HypothesisResult result;
    result.pValue = std::nan("");
    result.report = std::move(report);
    return result;
}
} // namespace

double sidakCorrection(double alpha, int testCount) { return 1.0 - std::pow(1.0 - alpha, 1.0 / testCount); }

HypothesisResult chi2Test(const std::vector<double> &observed, const std::vector<double> &expected,
                          double sampleCount, double minExpFrequency, double significanceLevel) {
    std::vector<size_t> order(expected.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });

    double statistic = 0.0, pooledObserved = 0.0, pooledExpected = 0.0;
    int dof = 0, pooledCells = 0;
    for (size_t cell : order) {
        const double o = observed[cell], e = expected[cell];
        if (!(e >= 0.0))
            return rejected(fmt::format("Encountered a negative (or NaN) expected number of samples ({}). "
                                        "Rejecting the null hypothesis!\n", e));
        if (e == 0.0) {
            // Sampling where the pdf says nothing can land is an error beyond rounding noise.
            if (o > sampleCount * 1e-5)
                return rejected(fmt::format("Encountered {} samples in a cell with expected frequency 0. "
                                            "Rejecting the null hypothesis!\n", o));
            continue;
        }
        if (e < minExpFrequency || (pooledCells > 0 && pooledExpected < minExpFrequency)) {
            pooledObserved += o;
            pooledExpected += e;
            ++pooledCells;
            continue;
        }
        statistic += (o - e) * (o - e) / e;
        ++dof;
    }
    std::string report;
    if (pooledCells > 0) {
        report += fmt::format("Pooled {} cells to ensure sufficiently high expected cell frequencies (>{})\n",
                              pooledCells, minExpFrequency);
        statistic += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
        ++dof;
    }
    dof -= 1;  // the counts sum to the sample count; no parameters were fitted
    if (dof <= 0)
        return rejected(report + fmt::format("The number of degrees of freedom ({}) is too low!\n", dof));
    report += fmt::format("Chi^2 statistic = {:.6g} (d.o.f. = {})\n", statistic, dof);

    HypothesisResult result;
    result.pValue = std::isfinite(statistic)
                        ? boost::math::cdf(boost::math::complement(boost::math::chi_squared(dof), statistic))
                        : std::nan("");
    result.accepted = result.pValue >= significanceLevel;  // false for NaN
    result.report = report + verdictLine(result.accepted, result.pValue, significanceLevel);
    return result;
}

HypothesisResult tTest(double sampleMean, double sampleVariance, uint64_t sampleCount, double reference,
                       double significanceLevel) {
    const double dof = double(sampleCount) - 1.0;
    const double t = std::abs(sampleMean - reference) * std::sqrt(double(sampleCount) / std::max(sampleVariance, 1e-5));
    std::string report = fmt::format("Sample mean = {:.6g} (reference value = {:.6g})\nSample variance = {:.6g}\n"
                                     "t-statistic = {:.6g} (d.o.f. = {})\n",
                                     sampleMean, reference, sampleVariance, t, sampleCount - 1);
    HypothesisResult result;
    if (!(dof >= 1.0) || !std::isfinite(t)) {
        result.pValue = std::nan("");
        result.report = report + "The p-value is not a valid number. Rejecting the null hypothesis!\n";
        return result;
    }
    result.pValue = 2.0 * boost::math::cdf(boost::math::complement(boost::math::students_t(dof), t));
    result.accepted = result.pValue >= significanceLevel;
    result.report = report + verdictLine(result.accepted, result.pValue, significanceLevel);
    return result;
}

} // namespace nori
