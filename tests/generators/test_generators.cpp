/// \file test_generators.cpp
/// \brief The generated scenes: deterministic, sized as asked, of the shape they claim, free
/// of degenerate triangles, and seen by their cameras.
#include <gtest/gtest.h>
#include <nori/bbox.h>
#include <error_of.h>
#include <ray_sets.h>
#include <scene_generator.h>
#include "mesh_measures.h"
#include <algorithm>
#include <map>
#include <cmath>

using namespace nori;
using namespace nori::gen;
using namespace nori::gen::test;

namespace {

/// Longest edge squared over twice the area: ~1 for a well-shaped triangle, large for a sliver.
double aspect(const MeshData &m, size_t f) {
    const auto &i = m.faces[f];
    Vector3d a = m.positions[i[0]].cast<double>(), b = m.positions[i[1]].cast<double>(),
             c = m.positions[i[2]].cast<double>();
    double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    return longest / (2.0 * area(m, f));
}

class EveryShape : public testing::TestWithParam<std::string> {};

TEST_P(EveryShape, DeterministicPerSeed) {
    GenParams p{20000, 7};
    GeneratedScene a = generateScene(GetParam(), p), b = generateScene(GetParam(), p);
    ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size());
    EXPECT_TRUE(std::equal(a.mesh.positions.begin(), a.mesh.positions.end(), b.mesh.positions.begin()));
    EXPECT_EQ(a.mesh.faces, b.mesh.faces);
    // A different seed changes the scene, except for the shapes that use no randomness.
    GeneratedScene c = generateScene(GetParam(), GenParams{20000, 8});
    bool same = c.mesh.positions.size() == a.mesh.positions.size() &&
                std::equal(a.mesh.positions.begin(), a.mesh.positions.end(), c.mesh.positions.begin());
    if (GetParam() != "coplanar") {
        EXPECT_FALSE(same);
    }
}

TEST_P(EveryShape, TriangleCountFollowsTheBudget) {
    for (uint64_t budget : {uint64_t(20000), findShape(GetParam())->defaultTriangles}) {
        GeneratedScene s = generateScene(GetParam(), GenParams{budget, 1});
        EXPECT_GT(double(s.triangleCount()), 0.85 * double(budget)) << budget;
        EXPECT_LT(double(s.triangleCount()), 1.15 * double(budget)) << budget;
    }
    EXPECT_EQ(generateScene(GetParam()).triangleCount(), generateScene(GetParam(), GenParams{0, 1}).triangleCount());
}

TEST_P(EveryShape, ValidGeometry) {
    GeneratedScene s = generateScene(GetParam(), GenParams{20000, 3});
    EXPECT_EQ(s.shape, GetParam());
    for (const Point3f &p : s.mesh.positions) ASSERT_TRUE(p.allFinite());
    for (size_t f = 0; f < s.mesh.faces.size(); ++f) {
        for (uint32_t i : s.mesh.faces[f]) ASSERT_LT(i, s.mesh.positions.size());
        ASSERT_GT(area(s.mesh, f), 0.0) << "degenerate triangle " << f;
    }
}

TEST_P(EveryShape, CameraSeesTheScene) {
    // At least a fifth of the camera's rays hit something (checked by brute force on a
    // coarse grid of pixels, through the same camera object the bench uses).
    uint64_t budget = std::max<uint64_t>(5000, findShape(GetParam())->minTriangles);
    GeneratedScene s = generateScene(GetParam(), GenParams{budget, 1});
    GenCamera small = s.camera;
    small.width = 24;
    small.height = 18;
    auto camera = makeCamera(small);
    Mesh mesh(s.mesh, "test");
    std::unique_ptr<Accel> brute = bruteForce(mesh);
    Accel &accel = *brute;
    size_t hits = 0, rays = 0;
    for (const Ray3f &ray : cameraRays(*camera, 1, 5)) {
        Hit hit;
        hits += accel.intersect(ray, hit) ? 1 : 0;
        ++rays;
    }
    EXPECT_GT(double(hits), 0.2 * double(rays));
}

// A placed scene (turned and moved far off, as a model placed at an angle in a georeferenced
// frame) is the same scene: every vertex where the rotation and offset put it (computed here in
// double with Eigen's own angle-axis form), and the camera moved with the mesh, so that its
// rays meet the same surfaces at the same distances (all but a few silhouette rays, which
// float coordinates of another magnitude may send past an edge; not the same triangle ids:
// where faces overlap, as in the coplanar shape, rounding picks one of them).
TEST_P(EveryShape, PlacementMovesMeshAndCameraTogether) {
    const uint64_t budget = std::max<uint64_t>(5000, findShape(GetParam())->minTriangles);
    GenParams placedParams{budget, 2};
    placedParams.placement = {Vector3f(1.0f, 2.0f, 0.5f), 33.0f, Vector3f(3000.0f, 1000.0f, -2000.0f)};
    const GeneratedScene plain = generateScene(GetParam(), GenParams{budget, 2});
    const GeneratedScene placed = generateScene(GetParam(), placedParams);
    ASSERT_EQ(placed.mesh.faces, plain.mesh.faces);
    ASSERT_EQ(placed.mesh.positions.size(), plain.mesh.positions.size());
    const Eigen::Matrix3d rotation =
        Eigen::AngleAxisd(33.0 * M_PI / 180.0, Eigen::Vector3d(1.0, 2.0, 0.5).normalized()).toRotationMatrix();
    const Eigen::Vector3d offset(3000.0, 1000.0, -2000.0);
    double worst = 0.0;
    for (size_t i = 0; i < plain.mesh.positions.size(); ++i) {
        const Eigen::Vector3d expected = rotation * plain.mesh.positions[i].cast<double>() + offset;
        worst = std::max(worst, (placed.mesh.positions[i].cast<double>() - expected).norm() / (1.0 + expected.norm()));
    }
    EXPECT_LT(worst, 1e-6) << "a vertex is not where the placement puts it";

    GenCamera smallPlain = plain.camera, smallPlaced = placed.camera;
    smallPlain.width = smallPlaced.width = 24;
    smallPlain.height = smallPlaced.height = 18;
    auto cameraPlain = makeCamera(smallPlain), cameraPlaced = makeCamera(smallPlaced);
    Mesh meshPlain(plain.mesh, "plain"), meshPlaced(placed.mesh, "placed");
    std::unique_ptr<Accel> brutePlain = bruteForce(meshPlain), brutePlaced = bruteForce(meshPlaced);
    const std::vector<Ray3f> raysPlain = cameraRays(*cameraPlain, 1, 5), raysPlaced = cameraRays(*cameraPlaced, 1, 5);
    ASSERT_EQ(raysPlain.size(), raysPlaced.size());
    size_t same = 0, hits = 0;
    for (size_t i = 0; i < raysPlain.size(); ++i) {
        Hit a, b;
        const bool hitA = brutePlain->intersect(raysPlain[i], a), hitB = brutePlaced->intersect(raysPlaced[i], b);
        hits += hitA;
        same += hitA == hitB && (!hitA || std::abs(a.t - b.t) <= 1e-3f * a.t);
    }
    EXPECT_GT(hits, 0u);
    EXPECT_GE(double(same), 0.97 * double(raysPlain.size())) << same << " of " << raysPlain.size() << " rays agree";
}

INSTANTIATE_TEST_SUITE_P(Shapes, EveryShape, testing::Values("city", "grass", "heightfield", "sphere", "room", "wide",
                                                             "tabletop", "stadium", "coplanar", "forest", "office",
                                                             "towers", "clutter", "hair", "sparse", "park",
                                                             "speck"));

TEST(Generators, EveryRegisteredShapeIsTested) {
    std::vector<std::string> tested = {"city",     "grass",  "heightfield", "sphere",  "room",
                                       "wide",     "tabletop", "stadium",   "coplanar", "forest",
                                       "office",   "towers",   "clutter",   "hair",     "sparse",
                                       "park",     "speck"};
    std::vector<std::string> registered;
    for (const ShapeInfo &s : shapes()) registered.push_back(s.name);
    EXPECT_EQ(registered, tested);
}

TEST(Generators, ShapesHaveTheirProportions) {
    BoundingBox3f city = boundsOf(generateScene("city").mesh);
    EXPECT_EQ(city.min, Point3f(-60, 0, -60));
    EXPECT_EQ(city.max, Point3f(60, 8, 60));

    BoundingBox3f strip = boundsOf(generateScene("heightfield").mesh);
    Vector3f e = strip.extents();
    EXPECT_GE(e.x() / e.y(), 900.0f);
    EXPECT_LE(e.x() / e.y(), 1100.0f);

    BoundingBox3f wide = boundsOf(generateScene("wide").mesh);
    e = wide.extents();
    EXPECT_GE(e.x() / e.y(), 900.0f);
    EXPECT_GE(e.z() / e.y(), 900.0f);

    BoundingBox3f cube = boundsOf(generateScene("coplanar").mesh);
    EXPECT_EQ(cube.min, Point3f(-1, -1, -1));
    EXPECT_EQ(cube.max, Point3f(1, 1, 1));

    // The room's camera is inside the room; the tabletop's ground dwarfs its objects.
    GeneratedScene room = generateScene("room");
    EXPECT_TRUE(boundsOf(room.mesh).contains(room.camera.origin));
    BoundingBox3f table = boundsOf(generateScene("tabletop").mesh);
    EXPECT_GE(table.extents().x() / table.extents().y(), 1000.0f);
}

TEST(Generators, GrassBladesAreLongAndThin) {
    GeneratedScene s = generateScene("grass", GenParams{20000, 1});
    std::vector<double> aspects;
    for (size_t f = 2; f < s.mesh.faces.size(); ++f) aspects.push_back(aspect(s.mesh, f));  // after the ground
    std::nth_element(aspects.begin(), aspects.begin() + aspects.size() / 2, aspects.end());
    EXPECT_GT(aspects[aspects.size() / 2], 20.0);
}

TEST(Generators, ClosedSurfacesAreWelded) {
    // The displaced sphere is one closed surface: every edge is shared by exactly two faces.
    GeneratedScene s = generateScene("sphere", GenParams{5000, 1});
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (const auto &f : s.mesh.faces)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = f[size_t(k)], b = f[size_t((k + 1) % 3)];
            ++edges[{std::min(a, b), std::max(a, b)}];
        }
    for (const auto &[edge, count] : edges) ASSERT_EQ(count, 2) << edge.first << "-" << edge.second;
}

TEST(Generators, BadParametersAreErrors) {
    EXPECT_NE(errorOf([] { generateScene("castle"); }).find("unknown scene shape 'castle'"), std::string::npos);
    EXPECT_NE(errorOf([] { generateScene("room", GenParams{10, 1}); }).find("needs between"), std::string::npos);
    EXPECT_NE(errorOf([] { generateScene("city", GenParams{uint64_t(1) << 40, 1}); }).find("needs between"),
              std::string::npos);
}

} // namespace
