/// \file test_hypothesis.cpp
/// \brief The statistics under the harnesses: chi^2 with pooling, the t-test, Sidak, and the
/// adaptive Simpson rule, against values from statistical tables and closed forms.
#include "validation/hypothesis.h"
#include "validation/simpson.h"
#include <cmath>
#include <gtest/gtest.h>

using namespace nori;

TEST(Sidak, MatchesNorisLevels) {
    // NORI-SPEC 4.3: alpha = 0.01 over 5, 2, 15 and 6 tests.
    EXPECT_NEAR(sidakCorrection(0.01, 5), 0.002008, 1e-6);
    EXPECT_NEAR(sidakCorrection(0.01, 2), 0.005013, 1e-6);
    EXPECT_NEAR(sidakCorrection(0.01, 15), 0.000670, 1e-6);
    EXPECT_NEAR(sidakCorrection(0.01, 6), 0.001674, 1e-6);
    EXPECT_NEAR(sidakCorrection(0.01, 1), 0.01, 1e-15);
}

TEST(ChiSquare, PValueOfTableValues) {
    // Two cells of 100 expected each; observed 100 +- d gives chi^2 = 2 d^2 / 100 with 1 d.o.f.
    // chi^2 = 3.841459 is the 95% quantile of chi^2(1) (tables): p = 0.05.
    const double d = std::sqrt(3.841459 * 100 / 2);
    HypothesisResult r = chi2Test({100 + d, 100 - d}, {100, 100}, 200, 5, 0.01);
    EXPECT_NEAR(r.pValue, 0.05, 1e-6);
    EXPECT_TRUE(r.accepted);
    EXPECT_NE(r.report.find("Chi^2 statistic = 3.84146 (d.o.f. = 1)"), std::string::npos) << r.report;
    r = chi2Test({100 + d, 100 - d}, {100, 100}, 200, 5, 0.06);
    EXPECT_FALSE(r.accepted);
    EXPECT_NE(r.report.find("***** Rejected *****"), std::string::npos);
    // chi^2(4) at 13.2767 is its 99% quantile.
    std::vector<double> expected(5, 1000.0), observed(5, 1000.0);
    observed[0] += std::sqrt(13.2767 * 1000 / 2);
    observed[1] -= std::sqrt(13.2767 * 1000 / 2);
    EXPECT_NEAR(chi2Test(observed, expected, 5000, 5, 0.01).pValue, 0.01, 1e-5);
}

TEST(ChiSquare, PoolsSparseCellsIntoOne) {
    // Four cells expecting 2 each are pooled into one (8 >= 5): 3 cells remain, 2 d.o.f.
    HypothesisResult r = chi2Test({2, 2, 2, 2, 50, 50}, {2, 2, 2, 2, 50, 50}, 108, 5, 0.01);
    EXPECT_NE(r.report.find("Pooled 4 cells"), std::string::npos) << r.report;
    EXPECT_NE(r.report.find("d.o.f. = 2"), std::string::npos) << r.report;
    EXPECT_NEAR(r.pValue, 1.0, 1e-12);
    // A pool still below the threshold swallows the next cell too: 1 + 1 + 2 < 5, then + 50.
    r = chi2Test({1, 1, 2, 50, 60}, {1, 1, 2, 50, 60}, 114, 5, 0.01);
    EXPECT_NE(r.report.find("Pooled 4 cells"), std::string::npos) << r.report;
    EXPECT_NE(r.report.find("d.o.f. = 1"), std::string::npos) << r.report;
}

TEST(ChiSquare, RejectsImpossibleSamplesAndTooFewCells) {
    // Samples where the density is zero (beyond 1e-5 of all samples).
    HypothesisResult r = chi2Test({500, 480, 20}, {500, 500, 0}, 1000, 5, 0.01);
    EXPECT_FALSE(r.accepted);
    EXPECT_NE(r.report.find("Encountered 20 samples in a cell with expected frequency 0"), std::string::npos);
    // A stray sample or two is rounding, not an error.
    EXPECT_TRUE(chi2Test({5e6, 5e6, 1}, {5e6, 5e6, 0}, 1e7, 5, 0.01).accepted);
    EXPECT_FALSE(chi2Test({10}, {10}, 10, 5, 0.01).accepted);  // 0 d.o.f.
    EXPECT_FALSE(chi2Test({10, 10}, {-1, 21}, 20, 5, 0.01).accepted);
}

TEST(TTest, PValueOfTableValues) {
    // t = 2.228139 is the two-sided 5% point of Student's t with 10 d.o.f. (tables):
    // mean off by t * sqrt(var / n) with n = 11, var = 4.
    const double offset = 2.228139 * std::sqrt(4.0 / 11.0);
    HypothesisResult r = tTest(3.0 + offset, 4.0, 11, 3.0, 0.01);
    EXPECT_NEAR(r.pValue, 0.05, 1e-6);
    EXPECT_TRUE(r.accepted);
    EXPECT_NE(r.report.find("t-statistic = 2.22814 (d.o.f. = 10)"), std::string::npos) << r.report;
    EXPECT_FALSE(tTest(3.0 + offset, 4.0, 11, 3.0, 0.06).accepted);
    // Symmetric in the sign of the deviation.
    EXPECT_NEAR(tTest(3.0 - offset, 4.0, 11, 3.0, 0.01).pValue, 0.05, 1e-6);
}

TEST(TTest, VarianceFloorAndNaN) {
    // Noiseless and exact: accepted; noiseless and off by 1e-3: t = 1e-3 sqrt(1e5 / 1e-5) = 100.
    EXPECT_TRUE(tTest(1.0, 0.0, 100000, 1.0, 0.01).accepted);
    EXPECT_FALSE(tTest(1.001, 0.0, 100000, 1.0, 0.01).accepted);
    HypothesisResult r = tTest(std::nan(""), 1.0, 1000, 1.0, 0.01);
    EXPECT_FALSE(r.accepted);
    EXPECT_NE(r.report.find("not a valid number"), std::string::npos);
}

TEST(Simpson, ExactForCubicsAndAccurateForSmoothFunctions) {
    EXPECT_NEAR(adaptiveSimpson([](double x) { return x * x * x - 2 * x; }, -1.0, 2.0), 0.75, 1e-12);
    EXPECT_NEAR(adaptiveSimpson([](double x) { return std::exp(x); }, 0.0, 1.0), std::exp(1.0) - 1.0, 1e-7);
    EXPECT_NEAR(adaptiveSimpson2D([](double x, double y) { return x * y * y; }, 0, 0, 2, 3), 18.0, 1e-12);
    // A narrow peak needs refinement: integral of a Gaussian of sigma 0.01 over +-0.1 is ~ 1.
    const double s = 0.01;
    auto gauss = [s](double x) { return std::exp(-x * x / (2 * s * s)) / (s * std::sqrt(2 * M_PI)); };
    EXPECT_NEAR(adaptiveSimpson(gauss, -0.1, 0.1, 1e-8, 12), 1.0, 1e-6);
}

TEST(Simpson, CellIntegralSeesAJumpOnTheEdgeFromInside) {
    // A density 1 for y >= 0 and 0 below, on the cells just below and just above the jump.
    auto step = [](double, double y) { return y >= 0.0 ? 1.0 : 0.0; };
    EXPECT_NEAR(integrateCell(step, 0, -0.1, 1, 0), 0.0, 1e-12);
    EXPECT_NEAR(integrateCell(step, 0, 0, 1, 0.1), 0.1, 1e-12);
}
