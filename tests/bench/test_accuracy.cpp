/// \file test_accuracy.cpp
/// \brief nori-bench's mismatch rule: t differences below float resolution of the scene's
/// coordinates are not mismatches; anything larger, or a hit/miss difference, is.
#include <gtest/gtest.h>
#include "../../bench/accuracy.h"

using namespace nori;
using nori::bench::Accuracy;

namespace {

TEST(BenchAccuracy, ToleranceFollowsTheCoordinateScale) {
    // A bounce off a wall at x = 1.59 into the adjacent wall 4.2e-5 away: the t of two exact
    // kernels differ by ~0.1 ulp of 1.59, i.e. 2e-4 of t itself.
    Ray3f nearHit(Point3f(1.59f, 0.3f, 0.2f), Vector3f(0.6f, 0.8f, 0.0f));
    std::vector<Ray3f> rays{nearHit, nearHit};
    Accuracy a = Accuracy::compare({4.17984047e-05f, 4.17984047e-05f + 3e-5f}, {4.17901974e-05f, 4.17901974e-05f}, rays);
    EXPECT_EQ(a.mismatches, 1u);  // the first is rounding; the second, 3e-5 apart (250 ulps), is not
    EXPECT_EQ(a.hitMiss, 0u);
    EXPECT_NEAR(a.maxRelTError, 0.718, 0.001);

    // Far hits keep the relative rule.
    Ray3f farHit(Point3f(0, 0, 0), Vector3f(0, 0, 1));
    a = Accuracy::compare({10.0f, 10.0005f, 10.002f}, {10.0f, 10.0f, 10.0f}, {farHit, farHit, farHit});
    EXPECT_EQ(a.mismatches, 1u);

    // Hit against miss, and the shadow encoding (0 = occluded, inf = free).
    a = Accuracy::compare({1.0f, Infinity, 0.0f, 0.0f}, {Infinity, 1.0f, 0.0f, Infinity}, {farHit, farHit, farHit, farHit});
    EXPECT_EQ(a.mismatches, 3u);
    EXPECT_EQ(a.hitMiss, 3u);
}

TEST(BenchAccuracy, SizesMustAgree) {
    EXPECT_THROW(Accuracy::compare({1.0f}, {1.0f}, {}), std::logic_error);
}

} // namespace
