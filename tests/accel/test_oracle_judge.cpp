/// \file test_oracle_judge.cpp
/// \brief The oracle's judge on hand-made disagreements: each verdict is given where it applies
/// and only there (a wrong answer stays unexplained).
#include <gtest/gtest.h>
#include <oracle_judge.h>
#include <cmath>

using namespace nori;

namespace {

Hit hit(float t, uint32_t prim) { return Hit{t, 0.0f, 0.0f, prim}; }
float hexf(const char *text) { return std::strtof(text, nullptr); }

/// A unit right triangle in z = 0 (prim 0), its duplicate (prim 1), the 2000-unit ground quad
/// of the tabletop scene in y = 0 (prims 2 and 3).
struct JudgeFixture : testing::Test {
    JudgeFixture() {
        MeshData data;
        data.positions = {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0),
                          Point3f(-1000, 0, -1000), Point3f(-1000, 0, 1000), Point3f(1000, 0, 1000),
                          Point3f(1000, 0, -1000)};
        data.faces = {{0, 1, 2}, {0, 1, 2}, {3, 4, 5}, {3, 5, 6}};
        mesh = std::make_unique<Mesh>(data, "judge");
        judge = std::make_unique<OracleJudge>(std::vector<const Mesh *>{mesh.get()});
    }
    std::unique_ptr<Mesh> mesh;
    std::unique_ptr<OracleJudge> judge;
};

TEST_F(JudgeFixture, MatchTieEdgeRange) {
    Ray3f down(Point3f(0.25f, 0.25f, 1.0f), Vector3f(0, 0, -1));
    EXPECT_EQ(judge->judge(down, false, Hit(), false, Hit()), Match);
    EXPECT_EQ(judge->judge(down, true, hit(1.0f, 0), true, hit(1.0000001f, 0)), Match);
    EXPECT_EQ(judge->judge(down, true, hit(1.0f, 1), true, hit(1.0f, 0)), Tie);  // duplicated triangle
    // One ulp inside the hypotenuse x + y = 1: a hit/miss disagreement there is an edge case.
    Ray3f nearEdge(Point3f(0.5f, std::nextafter(0.5f, 0.0f), 1.0f), Vector3f(0, 0, -1));
    EXPECT_EQ(judge->judge(nearEdge, true, hit(1.0f, 0), false, Hit()), Edge);
    // The segment ends on the triangle: hit or not is the range convention.
    Ray3f segment(Point3f(0.25f, 0.25f, 1.0f), Vector3f(0, 0, -1), 0.0f, 1.0f);
    EXPECT_EQ(judge->judge(segment, false, Hit(), true, hit(1.0f, 0)), Range);
}

TEST_F(JudgeFixture, WrongAnswersStayUnexplained) {
    Ray3f down(Point3f(0.25f, 0.25f, 1.0f), Vector3f(0, 0, -1));
    EXPECT_EQ(judge->judge(down, true, hit(1.001f, 0), true, hit(1.0f, 0)), Unexplained);  // t off by 1e-3
    EXPECT_EQ(judge->judge(down, false, Hit(), true, hit(1.0f, 0)), Unexplained);           // a clear hit missed
    Ray3f beside(Point3f(2.0f, 2.0f, 1.0f), Vector3f(0, 0, -1));
    EXPECT_EQ(judge->judge(beside, true, hit(1.0f, 0), false, Hit()), Unexplained);  // a clear miss hit
}

TEST_F(JudgeFixture, ExactAnswerAgainstAWrongOracle) {
    // Found by the scene oracle on "tabletop": the exact crossing lies 1.4e-4 on prim 3's side of
    // the quad's diagonal; Embree robust answered prim 2 (u = -1.2e-7 of a 2828-unit edge).
    Ray3f ray(Point3f(hexf("0x1.ccccccp-1"), hexf("0x1.59999ap+0"), hexf("0x1.4cccccp+0")),
              Vector3f(hexf("-0x1.0d2924p-1"), hexf("-0x1.070b12p-1"), hexf("-0x1.5b2352p-1")));
    EXPECT_EQ(judge->judge(ray, true, hit(2.62770486f, 3), true, hit(2.62770486f, 2)), OracleError);
    // Not the other way round: the accelerator's answer must be the exact one.
    EXPECT_EQ(judge->judge(ray, true, hit(2.62770486f, 2), true, hit(2.62770486f, 3)), Unexplained);
    // Nor when the accelerator's t is off (the watertight fault on this quad, 2e-4 too far).
    Ray3f camera(Point3f(hexf("0x1.ccccccp-1"), hexf("0x1.59999ap+0"), hexf("0x1.4cccccp+0")),
                 Vector3f(hexf("-0x1.7cebf6p-1"), hexf("-0x1.cc0dfep-3"), hexf("-0x1.4233dep-1")));
    EXPECT_EQ(judge->judge(camera, true, hit(6.00992537f, 2), true, hit(6.0097208f, 2)), Unexplained);
    EXPECT_EQ(judge->judge(camera, true, hit(6.0097208f, 2), true, hit(6.0097208f, 2)), Match);
}

TEST_F(JudgeFixture, KernelCornerScaleExplainsFloatLeaksOnlyNearEdges) {
    // Straight down onto the 2000-unit ground quad, 0.001 beside its diagonal x = z (prim 3's
    // side), 1 above it: a miss of both ground triangles there is a leak of a float kernel whose
    // coordinates near 1000 round to about 2^-17 of that, 0.0076. At the problem's scale (the
    // ray's coordinates, about 1) it stays unexplained.
    OracleJudge corners({mesh.get()}, OracleJudge::EdgeScale::KernelCorners);
    Ray3f nearDiagonal(Point3f(0.5f, 1.0f, 0.499f), Vector3f(0, -1, 0));
    EXPECT_EQ(judge->judge(nearDiagonal, false, Hit(), true, hit(1.0f, 3)), Unexplained);
    EXPECT_EQ(corners.judge(nearDiagonal, false, Hit(), true, hit(1.0f, 3)), Edge);
    // 0.1 beside the diagonal is far beyond that rounding: a miss there is wrong at both scales.
    Ray3f clear(Point3f(0.5f, 1.0f, 0.4f), Vector3f(0, -1, 0));
    EXPECT_EQ(judge->judge(clear, false, Hit(), true, hit(1.0f, 3)), Unexplained);
    EXPECT_EQ(corners.judge(clear, false, Hit(), true, hit(1.0f, 3)), Unexplained);
}

} // namespace

// The exact referee of nori-bench's mismatch counts: right, wrong and undecidable answers.
TEST_F(JudgeFixture, RefereeDecidesInExactArithmetic) {
    const std::vector<uint32_t> unit{0};
    Ray3f down(Point3f(0.25f, 0.25f, 1.0f), Vector3f(0, 0, -1));
    EXPECT_EQ(judge->referee(down, true, hit(1.0f, 0), unit), 1);
    EXPECT_EQ(judge->referee(down, false, Hit(), unit), -1);  // a clear hit missed
    // One ulp outside the hypotenuse x + y = 1 (0.5 + 0.5 + 2^-24 > 1): a hit there is wrong,
    // a miss right, although every float edge test is within its rounding.
    Ray3f outside(Point3f(0.5f, std::nextafter(0.5f, 1.0f), 1.0f), Vector3f(0, 0, -1));
    EXPECT_EQ(judge->referee(outside, true, hit(1.0f, 0), unit), -1);
    EXPECT_EQ(judge->referee(outside, false, Hit(), unit), 1);
    Ray3f inside(Point3f(0.5f, std::nextafter(0.5f, 0.0f), 1.0f), Vector3f(0, 0, -1));
    EXPECT_EQ(judge->referee(inside, true, hit(1.0f, 0), unit), 1);
    EXPECT_EQ(judge->referee(inside, false, Hit(), unit), -1);
    // Exactly on the edge: undecidable, for a hit and for a miss.
    Ray3f onEdge(Point3f(0.5f, 0.5f, 1.0f), Vector3f(0, 0, -1));
    EXPECT_EQ(judge->referee(onEdge, true, hit(1.0f, 0), unit), 0);
    EXPECT_EQ(judge->referee(onEdge, false, Hit(), unit), 0);
    // Several candidates: a ray along -y from (0.25, 1, -0.5) misses the unit triangle (it never
    // reaches z = 0) and meets the ground on prim 3's side of its diagonal x = z.
    Ray3f toGround(Point3f(0.25f, 1.0f, -0.5f), Vector3f(0, -1, 0));
    EXPECT_EQ(judge->referee(toGround, true, hit(1.0f, 3), {0, 2, 3}), 1);
    EXPECT_EQ(judge->referee(toGround, true, hit(1.0f, 2), {0, 2, 3}), -1);
    EXPECT_EQ(judge->referee(toGround, false, Hit(), {0, 2, 3}), -1);
    // A ray one ulp beside the quad's diagonal (x = z) names either triangle rightly: the same
    // point, within rounding of both.
    Ray3f diagonal(Point3f(0.25f, 1.0f, std::nextafter(0.25f, 1.0f)), Vector3f(0, -1, 0));
    EXPECT_EQ(judge->referee(diagonal, true, hit(1.0f, 2), {2, 3}), 1);
    EXPECT_EQ(judge->referee(diagonal, true, hit(1.0f, 3), {2, 3}), 1);
    // A hit beyond the segment's end: the segment [0, 0.5] of `down` stops short of the triangle.
    Ray3f shortDown(Point3f(0.25f, 0.25f, 1.0f), Vector3f(0, 0, -1), 0.0f, 0.5f);
    EXPECT_EQ(judge->referee(shortDown, true, hit(1.0f, 0), unit), -1);
    EXPECT_EQ(judge->referee(shortDown, false, Hit(), unit), 1);
    EXPECT_EQ(judge->referee(toGround, true, hit(1.0f, 0), {0, 2, 3}), -1);
}
