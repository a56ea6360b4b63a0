/// \file test_triangle_plane_t.cpp
/// \brief t where the kernels recompute it from the plane (exactPlaneT, src/accel/triangle.cpp):
/// on huge floors and walls (three corners sharing a coordinate: t = (p_a - o_a) / d_a), on
/// huge planes tilted by 2^-2 .. 2^-20 and on ramps whose corners share no coordinate (the
/// normal and two dot products in double), t is the exact t rounded, at every lane width.
#include <gtest/gtest.h>
#include <nori/accel.h>
#include <accel/triangle.h>
#include "exact_triangle.h"
#include <pcg_random.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>

using namespace nori;

namespace {

/// One leaf of \p tris (at most 16), watertight.
TriangleStore leafOf(const std::vector<std::array<Point3f, 3>> &tris) {
    std::vector<uint32_t> ids(tris.size());
    for (uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
    TriangleStore store;
    store.reset(Intersector::Watertight, TriangleStore::leafWords(uint32_t(ids.size())));
    store.setLeaf(0, ids.data(), uint32_t(ids.size()), tris);
    return store;
}

/// Sixteen triangles 2000 across around the origin: halves of a floor (y = 0) and of two walls
/// (x = 3, z = -5: floats whose differences are exact), seven floor triangles whose far corners
/// rise by 2000 * 2^-k (k = 2, 5, ..., 20: from steep to tilted by less than the float
/// resolution of their corners; two corners share x, two others z), and three ramps
/// y ~ 0.37 z + 2^-k x whose corners share no coordinate.
std::vector<std::array<Point3f, 3>> hugePlanes() {
    std::vector<std::array<Point3f, 3>> tris = {
        {Point3f(-1000, 0, -1000), Point3f(-1000, 0, 1000), Point3f(1000, 0, 1000)},
        {Point3f(-1000, 0, -1000), Point3f(1000, 0, 1000), Point3f(1000, 0, -1000)},
        {Point3f(3, -1000, -1000), Point3f(3, 1000, -1000), Point3f(3, 1000, 1000)},
        {Point3f(3, -1000, -1000), Point3f(3, 1000, 1000), Point3f(3, -1000, 1000)},
        {Point3f(-1000, -1000, -5), Point3f(1000, -1000, -5), Point3f(1000, 1000, -5)},
        {Point3f(-1000, -1000, -5), Point3f(1000, 1000, -5), Point3f(-1000, 1000, -5)},
    };
    for (int k : {2, 5, 8, 11, 14, 17, 20}) {
        const float rise = std::ldexp(2000.0f, -k);
        if (tris.size() % 2)
            tris.push_back({Point3f(-1000, 0, -1000), Point3f(-1000, rise, 1000), Point3f(1000, 0.37f * rise, 1000)});
        else
            tris.push_back({Point3f(-1000, -0.5f * rise, -1000), Point3f(1000, 0.0f, -1000), Point3f(0, rise, 1000)});
    }
    for (int k : {8, 16, 24}) {
        auto ramp = [k](float x, float z) { return Point3f(x, 0.37f * z + std::ldexp(x, -k), z); };
        tris.push_back({ramp(-1013.3f, 0.7f), ramp(1021.7f, -1003.9f), ramp(-7.9f, 1011.1f)});
    }
    return tris;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

// Rays from 2^-21 .. 2 above a plane, aimed at points of it 0.5 .. 60 away from the origin's
// foot (hit distances 1e-6 .. 1e2 times the triangles' size), and rays leaving it. Every hit
// whose t came from the plane in double (the lanes that skipped the inside test: crossing
// strictly inside) must carry the exact t within 2^-22 of it (the double result rounded once
// to float, plus slack); every other hit the oracle's 2^-17 of the problem's scale; every width
// the 1-lane answer bit for bit. A shortcut that took a triangle for axis-aligned on fewer than
// all three corners (the tilted triangles share x between two corners and z between two others)
// fails here, as would one that divided by the wrong component of d.
TEST(TrianglePlaneT, RecomputedTIsTheExactTRounded) {
    pcg32 rng(20261123);
    auto uniform = [&](float a, float b) { return a + (b - a) * float(rng() >> 8) * 0x1p-24f; };
    const std::vector<std::array<Point3f, 3>> tris = hugePlanes();
    const TriangleStore store = leafOf(tris);
    size_t exactPath[2] = {0, 0}, other = 0, bad = 0, differ = 0;
    double worst = 0.0;
    for (int k = 0; k < 40000; ++k) {
        // A foot point on the plane of a random triangle near the world origin, the origin 2^-20
        // .. 2 above it, and a target on the plane 0.5 .. 60 from the foot (or, one ray in
        // eight, a direction away from the plane).
        const auto &p = tris[rng() % tris.size()];
        const Eigen::Vector3d a = p[0].cast<double>(), n = (p[1].cast<double>() - a).cross(p[2].cast<double>() - a).normalized();
        const Eigen::Vector3d r(uniform(-10, 10), uniform(-10, 10), uniform(-10, 10));
        const Eigen::Vector3d foot = r - n.dot(r - a) * n;
        const double h = std::ldexp(double(uniform(1, 2)), -int(rng() % 22));
        const Point3f o = (foot + h * n).cast<float>();
        Eigen::Vector3d side = n.cross(Eigen::Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
        if (side.norm() < 1e-3) continue;
        side *= std::exp(double(uniform(std::log(0.5f), std::log(60.0f)))) / side.norm();
        const Vector3f d = k % 8 == 7 ? (n * double(uniform(0.01f, 1)) + side.normalized()).cast<float>().eval()
                                      : ((foot + side).cast<float>() - o).eval();
        if (d.isZero()) continue;
        const Ray3f ray(o, d);
        const TriangleRay tr(ray);
        TriangleStore::ChunkAnswers ref;
        store.chunkAnswers(1, tr, 0, uint32_t(tris.size()), 0, ray.maxt, ref);
        for (int width : TriangleStore::laneWidths()) {
            TriangleStore::ChunkAnswers ans;
            store.chunkAnswers(width, tr, 0, uint32_t(tris.size()), 0, ray.maxt, ans);
            bool same = ans.hits == ref.hits && ans.insideKnown == ref.insideKnown;
            for (size_t s = 0; s < tris.size(); ++s)
                if ((ref.hits >> s) & 1u) same = same && sameBits(ans.t[s], ref.t[s]);
            differ += !same;
        }
        const double dn = ray.d.cast<double>().norm(), oInf = ray.o.cast<double>().cwiseAbs().maxCoeff();
        for (size_t s = 0; s < tris.size(); ++s) {
            if (!((ref.hits >> s) & 1u)) continue;
            const exact::GeometricAnswer e = exact::geometric(ray, tris[s][0], tris[s][1], tris[s][2]);
            const double apart = std::abs(double(ref.t[s]) - e.t);
            double tol;
            if ((ref.insideKnown >> s) & 1u) {
                ++exactPath[s < 6 ? 0 : 1];
                tol = 0x1p-22 * std::abs(e.t) + 0x1p-140;
                worst = std::max(worst, apart / tol);
            } else {
                ++other;
                tol = 0x1p-17 * std::max(oInf, std::abs(e.t) * dn) / dn;
            }
            if (!(apart <= tol) && ++bad <= 5)
                ADD_FAILURE() << "triangle " << s << ((ref.insideKnown >> s) & 1u ? " (t in double)" : "") << ": t " << ref.t[s]
                              << ", exact " << e.t << ", " << apart / tol << "x the tolerance; o " << o.transpose() << " d "
                              << d.transpose();
        }
    }
    std::printf("[ plane t  ] t in double: %zu hits on floors and walls, %zu on tilted planes (worst %.3g of 2^-22 t); %zu other hits\n",
                exactPath[0], exactPath[1], worst, other);
    EXPECT_EQ(bad, 0u);
    EXPECT_EQ(differ, 0u) << "widths differ from 1 lane";
    EXPECT_GT(exactPath[0], 5000u);  // floors and walls take the axis-aligned plane
    EXPECT_GT(exactPath[1], 5000u);  // tilted planes and ramps the general one
    EXPECT_GT(other, 1000u);
}

} // namespace
