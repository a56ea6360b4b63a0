/// \file test_shape_traits.cpp
/// \brief The shapes added for scenes nobody tuned on (forest, office, towers, clutter, hair,
/// sparse, park, speck) have the property each one is there for: the tests measure it on the mesh.
#include <gtest/gtest.h>
#include <nori/accel.h>
#include <nori/bbox.h>
#include <scene_generator.h>
#include "mesh_measures.h"
#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace nori;
using namespace nori::gen;
using namespace nori::gen::test;

namespace {

/// The \p q quantile (0..1) of \p values.
double quantile(std::vector<double> values, double q) {
    auto at = values.begin() + std::ptrdiff_t(q * double(values.size() - 1));
    std::nth_element(values.begin(), at, values.end());
    return *at;
}

/// Distance to the first hit along the camera's central ray (brute force), infinity if none.
float centralHitDistance(const GeneratedScene &s) {
    Mesh mesh(s.mesh, "test");
    std::unique_ptr<Accel> brute = bruteForce(mesh);
    Accel &accel = *brute;
    Hit hit;
    Ray3f ray(s.camera.origin, (s.camera.target - s.camera.origin).normalized());
    return accel.intersect(ray, hit) ? hit.t : Infinity;
}

TEST(ShapeTraits, ForestLeavesFillAVolume) {
    // Most triangles are leaves of a few square centimetres, spread over metres of height.
    GeneratedScene s = generateScene("forest", GenParams{20000, 1});
    std::vector<double> areas, heights;
    for (size_t f = 0; f < s.mesh.faces.size(); ++f) {
        areas.push_back(area(s.mesh, f));
        heights.push_back(triangleBounds(s.mesh, f).center().y());
    }
    EXPECT_LT(quantile(areas, 0.5), 0.01);
    EXPECT_GT(quantile(heights, 0.75) - quantile(heights, 0.25), 2.0);
    EXPECT_GT(centralHitDistance(s), 5.0f);  // the camera stands clear of every crown
}

TEST(ShapeTraits, OfficeCameraLooksDownACorridor) {
    GeneratedScene s = generateScene("office");
    BoundingBox3f b = boundsOf(s.mesh);
    EXPECT_TRUE(b.contains(s.camera.origin));
    // The view runs most of the storey's length before it meets a wall.
    EXPECT_GT(centralHitDistance(s), 0.8f * b.extents().x());
    // Thin walls: boxes 12 cm thick and 3 m high are a large share of the triangles.
    size_t thin = 0;
    for (size_t f = 0; f < s.mesh.faces.size(); ++f) {
        Vector3f e = triangleBounds(s.mesh, f).extents();
        thin += (e.y() > 2.9f && std::min(e.x(), e.z()) < 0.2f && std::max(e.x(), e.z()) < 0.2f) ? 1 : 0;
    }
    EXPECT_GT(thin, 1000u);
}

TEST(ShapeTraits, TowersAreTallerThanWide) {
    GeneratedScene s = generateScene("towers");
    Vector3f e = boundsOf(s.mesh).extents();
    EXPECT_GE(e.y() / e.x(), 6.0f);
    EXPECT_GE(e.y() / e.z(), 6.0f);
    EXPECT_LT(s.camera.width, s.camera.height);  // a portrait frame
}

TEST(ShapeTraits, ClutterSpansFourDecadesOfTriangleSize) {
    GeneratedScene s = generateScene("clutter", GenParams{20000, 1});
    std::vector<double> areas;
    for (size_t f = 0; f < s.mesh.faces.size(); ++f) areas.push_back(area(s.mesh, f));
    auto [lo, hi] = std::minmax_element(areas.begin(), areas.end());
    EXPECT_GT(*hi / *lo, 1e8);  // edge lengths over four decades
    // Every decade of stone size is present: pebble triangles under 1e-4, boulder ones over 1.
    EXPECT_LT(quantile(areas, 0.05), 1e-4);
    EXPECT_GT(quantile(areas, 0.8), 1.0);
}

TEST(ShapeTraits, HairIsMadeOfSliversOutsideTheHead) {
    GeneratedScene s = generateScene("hair", GenParams{20000, 1});
    size_t slivers = 0, inside = 0;
    for (size_t f = 0; f < s.mesh.faces.size(); ++f) {
        const auto &i = s.mesh.faces[f];
        Vector3d a = s.mesh.positions[i[0]].cast<double>(), b = s.mesh.positions[i[1]].cast<double>(),
                 c = s.mesh.positions[i[2]].cast<double>();
        double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
        slivers += longest / (2.0 * area(s.mesh, f)) > 8.0 ? 1 : 0;
    }
    for (const Point3f &p : s.mesh.positions) inside += p.norm() < 0.999f ? 1 : 0;
    EXPECT_GT(double(slivers), 0.8 * double(s.mesh.faces.size()));
    EXPECT_EQ(inside, 0u);  // no strand grows into the head
    // Long strands: the hair hangs well below the head's radius.
    EXPECT_LT(boundsOf(s.mesh).min.y(), -1.4f);
}

TEST(ShapeTraits, SparseIsMostlyEmpty) {
    GeneratedScene s = generateScene("sparse");
    BoundingBox3f b = boundsOf(s.mesh);
    double occupied = 0.0;
    size_t tilted = 0;
    for (size_t f = 0; f < s.mesh.faces.size(); ++f) {
        BoundingBox3f t = triangleBounds(s.mesh, f);
        Vector3f e = t.extents();
        if (e.x() > 0.3f * b.extents().x()) {
            tilted += e.minCoeff() > 100.0f ? 1 : 0;  // huge and not in an axis plane
            continue;
        }
        occupied += double(e.x()) * double(e.y()) * double(e.z());
    }
    EXPECT_EQ(tilted, 8u);
    // The triangles' boxes (overlaps counted twice) fill less than a millionth of the bounds.
    EXPECT_LT(occupied / (double(b.extents().x()) * b.extents().y() * b.extents().z()), 1e-6);
}

TEST(ShapeTraits, ParkIsACardForestInsideASkyWithFans) {
    GeneratedScene s = generateScene("park", GenParams{20000, 1});
    // Closed around the camera: a ray in any direction ends somewhere (1024 directions spread
    // over the sphere, a Fibonacci lattice: the nearest to straight up lies 2.5 degrees off it,
    // inside the polar fan).
    Mesh mesh(s.mesh, "park");
    std::unique_ptr<Accel> brute = bruteForce(mesh);
    int escaped = 0;
    for (int k = 0; k < 1024; ++k) {
        const float z = 1.0f - (2.0f * float(k) + 1.0f) / 1024.0f, r = std::sqrt(1.0f - z * z);
        const float phi = 2.399963f * float(k);  // the golden angle
        Hit hit;
        escaped += brute->intersect(Ray3f(s.camera.origin, Vector3f(r * std::cos(phi), z, r * std::sin(phi))), hit) ? 0 : 1;
    }
    EXPECT_EQ(escaped, 0);
    // Poles: a vertex that dozens of slivers share.
    std::vector<int> valence(s.mesh.positions.size(), 0);
    for (const auto &f : s.mesh.faces)
        for (uint32_t v : f) ++valence[v];
    EXPECT_GE(*std::max_element(valence.begin(), valence.end()), 32);
    // Most triangles are halves of vertical cards metres tall, and each tree's two cards cross:
    // the midpoints of a card's two bottom corners coincide with its partner's.
    size_t cards = 0;
    for (size_t f = 0; f < s.mesh.faces.size(); ++f) {
        const Vector3f e = triangleBounds(s.mesh, f).extents();
        cards += (e.y() >= 2.0f && e.y() <= 8.0f && triangleBounds(s.mesh, f).min.y() == 0.0f) ? 1 : 0;
    }
    EXPECT_GT(double(cards), 0.75 * double(s.mesh.faces.size()));
    size_t crossed = 0, checked = 0;
    for (size_t f = s.mesh.faces.size() - 400; f + 3 < s.mesh.faces.size(); f += 4) {  // tree by tree, at the end
        auto bottomMid = [&](size_t face) {  // quad (a, b, c, d) is faces (a, b, c), (a, c, d): a and b on the ground
            const auto &t = s.mesh.faces[face];
            return 0.5f * (s.mesh.positions[t[0]] + s.mesh.positions[t[1]]);
        };
        ++checked;
        crossed += (bottomMid(f) - bottomMid(f + 2)).norm() < 1e-4f ? 1 : 0;
    }
    EXPECT_EQ(crossed, checked);
}

TEST(ShapeTraits, SpeckLooksAtAHugeGroundsDiagonalUnderARock) {
    GeneratedScene s = generateScene("speck", GenParams{8000, 1});
    // The ground: the first two faces, one quad 100,000 across split along x = z; the rest is
    // the rock, about 1 across, standing across that diagonal.
    BoundingBox3f ground = triangleBounds(s.mesh, 0);
    ground.expandBy(triangleBounds(s.mesh, 1));
    BoundingBox3f rock;
    for (size_t f = 2; f < s.mesh.faces.size(); ++f) rock.expandBy(triangleBounds(s.mesh, f));
    EXPECT_GE(ground.extents().x(), 5e4f * rock.extents().maxCoeff());
    EXPECT_LE(rock.extents().maxCoeff(), 1.5f);
    EXPECT_GT(rock.max.y(), 0.0f);
    auto shared = [&](uint32_t v) {
        for (uint32_t w : s.mesh.faces[1])
            if (w == v) return true;
        return false;
    };
    int common = 0;
    for (uint32_t v : s.mesh.faces[0]) {
        if (!shared(v)) continue;
        ++common;
        const Point3f &p = s.mesh.positions[v];
        EXPECT_EQ(p.x(), p.z()) << "the shared edge runs along x = z";
    }
    EXPECT_EQ(common, 2);
    EXPECT_LT(rock.min.x() - rock.max.z(), 0.0f) << "the diagonal passes under the rock";
    EXPECT_GT(rock.max.x() - rock.min.z(), 0.0f) << "the diagonal passes under the rock";
    // Of the ground the camera sees, more than a third lies within 1 of the diagonal. On
    // triangles this large the float edge test's error bound leaves a band about that wide
    // around their edges undecided (its products of two coordinates near 50,000 are uncertain
    // by hundreds of units), and the rays there take the exact path. A 64 x 48 grid of camera
    // rays, brute force.
    Mesh mesh(s.mesh, "speck");
    std::unique_ptr<Accel> brute = bruteForce(mesh);
    std::unique_ptr<Camera> camera = makeCamera(s.camera);
    int groundHits = 0, nearDiagonal = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            Ray3f ray;
            const Point2f pixel((float(x) + 0.5f) / 64.0f * float(s.camera.width),
                                (float(y) + 0.5f) / 48.0f * float(s.camera.height));
            camera->sampleRay(ray, pixel, Point2f(0.5f, 0.5f));
            Hit hit;
            if (!brute->intersect(ray, hit) || hit.prim > 1) continue;
            const Point3f p = ray(hit.t);
            ++groundHits;
            nearDiagonal += std::abs(p.x() - p.z()) / std::sqrt(2.0f) < 1.0f ? 1 : 0;
        }
    std::printf("[traits] speck: %d of %d ground hits within 1 of the diagonal\n", nearDiagonal, groundHits);
    EXPECT_GT(groundHits, 64 * 48 / 3);
    EXPECT_GT(nearDiagonal, groundHits / 3);
}

} // namespace
