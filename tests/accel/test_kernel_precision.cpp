/// \file test_kernel_precision.cpp
/// \brief The kernel precision faults the scene oracle found (issue 9), as minimal rays, and a
/// randomized check of t on the kinds of triangles that caused them. Each test states what a
/// correct kernel must answer: the exact answer in double, within the oracle's eps of 2^-17 of
/// the problem's scale. The first three failed before the kernels recomputed an ill-conditioned
/// t from the plane equation in double (src/accel/triangle.cpp, exactPlaneT).
#include <gtest/gtest.h>
#include <nori/accel.h>
#include <nori/object.h>
#include <accel/triangle.h>
#include <pcg_random.hpp>
#include <cmath>
#include <cstring>

using namespace nori;

namespace {

/// Closest hit of \p ray against \p mesh with the brute-force accel and \p intersector (the
/// same kernels as the octree's leaves).
bool trace(const MeshData &mesh, const char *intersector, const Ray3f &ray, Hit &hit) {
    Mesh m(mesh, "repro");
    PropertyList props;
    props.setString("intersector", intersector);
    std::unique_ptr<NoriObject> object = NoriObjectFactory::createInstance(NoriObject::EAccel, "brute", props);
    auto &accel = static_cast<Accel &>(*object);
    accel.addMesh(&m);
    accel.build();
    return accel.intersect(ray, hit);
}

float hexf(const char *text) { return std::strtof(text, nullptr); }

/// The tabletop scene's ground: a quad 2000 across in the plane y = 0.
MeshData groundQuad() {
    MeshData m;
    m.positions = {Point3f(-1000, 0, -1000), Point3f(-1000, 0, 1000), Point3f(1000, 0, 1000), Point3f(1000, 0, -1000)};
    m.faces = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

// A camera ray 1.35 above the ground hits it 6 units away. Exact: t = 1.35 / 0.2246 = 6.0097208
// (Embree robust, Embree default and the octree's mt all give 6.0097208). The watertight
// kernel's float t was 6.0099254: 2.0e-4 too far, 4.4x the eps of the ray's scale, because it
// comes from sheared vertex coordinates of magnitude |v - o| ~ 1400 (scale-ups of ulp(1400)).
TEST(KernelPrecision, WatertightTOnLargeTriangle) {
    Ray3f ray(Point3f(hexf("0x1.ccccccp-1"), hexf("0x1.59999ap+0"), hexf("0x1.4cccccp+0")),
              Vector3f(hexf("-0x1.7cebf6p-1"), hexf("-0x1.cc0dfep-3"), hexf("-0x1.4233dep-1")));
    double exact = -double(ray.o.y()) / double(ray.d.y());
    double eps = 0x1p-17 * exact * ray.d.cast<double>().norm();
    for (const char *kernel : {"mt", "watertight"}) {
        Hit hit;
        ASSERT_TRUE(trace(groundQuad(), kernel, ray, hit)) << kernel;
        EXPECT_LE(std::abs(double(hit.t) - exact) * ray.d.cast<double>().norm(), eps)
            << kernel << ": t " << hit.t << ", exact " << exact;
    }
}

// A diffuse bounce leaving the ground 3.0e-5 above it, upwards: it can never meet the ground
// (exact t on the plane: -5.6e-5). The watertight kernel's float t reported a hit at
// t = 1.1e-4 (its t error on this 2000-unit triangle exceeds the distance to the plane), so an
// integrator spawning rays from the ground saw its own surface. mt and both Embree modes miss.
TEST(KernelPrecision, WatertightSelfHitOnLargeTriangle) {
    Ray3f ray(Point3f(hexf("-0x1.e6edf2p+2"), hexf("0x1.f6868ap-16"), hexf("-0x1.f6868ap+2")),
              Vector3f(hexf("-0x1.e4a77ep-2"), hexf("0x1.113b6cp-1"), hexf("-0x1.66d6e8p-1")));
    ASSERT_GT(ray.o.y(), 0.0f);
    ASSERT_GT(ray.d.y(), 0.0f);
    for (const char *kernel : {"mt", "watertight"}) {
        Hit hit;
        EXPECT_FALSE(trace(groundQuad(), kernel, ray, hit)) << kernel << ": hit at t " << hit.t;
    }
}

// A grass blade: a sliver 0.44 long whose two tip corners are 2e-3 apart, hit head-on
// (sin of the angle to its plane 0.6) 11.3 units away. Exact t 11.2951568; watertight
// 11.2951565, Embree robust 11.2951584, Embree default 11.2951555, mt's float t 11.2949743:
// 1.8e-4 short, 2.1x the eps (its det and t are cross products of two nearly parallel edges).
TEST(KernelPrecision, MtTOnSliver) {
    MeshData blade;
    blade.positions = {Point3f(hexf("-0x1.5bfd08p+0"), 0.0f, hexf("-0x1.2afa86p+2")),
                       Point3f(hexf("-0x1.8f0952p+0"), hexf("0x1.c63724p-2"), hexf("-0x1.35c70ap+2")),
                       Point3f(hexf("-0x1.8ec5e6p+0"), hexf("0x1.c63724p-2"), hexf("-0x1.35e57ep+2"))};
    blade.faces = {{0, 1, 2}};
    Ray3f ray(Point3f(hexf("0x1.99999ap-1"), hexf("0x1.19999ap+0"), hexf("0x1.8cccccp+2")),
              Vector3f(hexf("-0x1.a8e4f2p-3"), hexf("-0x1.f4875p-5"), hexf("-0x1.f3e1c4p-1")));
    // Exact t on the blade's plane, in double.
    Eigen::Vector3d a = blade.positions[0].cast<double>(), b = blade.positions[1].cast<double>(),
                    c = blade.positions[2].cast<double>();
    Eigen::Vector3d n = (b - a).cross(c - a);
    double exact = n.dot(a - ray.o.cast<double>()) / n.dot(ray.d.cast<double>());
    double eps = 0x1p-17 * exact * ray.d.cast<double>().norm();
    for (const char *kernel : {"watertight", "mt"}) {
        Hit hit;
        ASSERT_TRUE(trace(blade, kernel, ray, hit)) << kernel;
        EXPECT_LE(std::abs(double(hit.t) - exact) * ray.d.cast<double>().norm(), eps)
            << kernel << ": t " << hit.t << ", exact " << exact;
    }
}

/// Exact t of \p ray on the plane of \p p, sin of the angle between the ray and the plane, and
/// the smallest barycentric coordinate of the crossing (negative: outside the triangle).
double exactPlaneT(const std::array<Point3f, 3> &p, const Ray3f &ray, double &sinAngle, double &minBary) {
    Eigen::Vector3d a = p[0].cast<double>(), n = (p[1].cast<double>() - a).cross(p[2].cast<double>() - a);
    Eigen::Vector3d o = ray.o.cast<double>(), d = ray.d.cast<double>();
    sinAngle = std::abs(n.dot(d)) / (n.norm() * d.norm());
    const double t = n.dot(a - o) / n.dot(d);
    const Eigen::Vector3d x = o + t * d;
    minBary = 1.0;
    for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d u = p[size_t(k)].cast<double>(), v = p[size_t(k + 1) % 3].cast<double>();
        minBary = std::min(minBary, (v - u).cross(x - u).dot(n) / n.squaredNorm());
    }
    return t;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

/// Sixteen triangles where float t goes wrong: two halves of a 2000-unit ground quad in y = 0,
/// two huge tilted triangles, eight slivers (long axis ~1, width 1e-2 .. 1e-4) and four ordinary
/// triangles anywhere in [-8, 8]^3, drawn from \p uniform.
template <typename Uniform>
std::vector<std::array<Point3f, 3>> hardTriangles(Uniform &uniform) {
    std::vector<std::array<Point3f, 3>> tris = {
        {Point3f(-1000, 0, -1000), Point3f(-1000, 0, 1000), Point3f(1000, 0, 1000)},
        {Point3f(-1000, 0, -1000), Point3f(1000, 0, 1000), Point3f(1000, 0, -1000)},
        {Point3f(-1300, -400, -900), Point3f(1100, 250, -1000), Point3f(100, -30, 1200)},
        {Point3f(-900, 700, 1000), Point3f(1000, -650, 1100), Point3f(50, 20, -1400)},
    };
    while (tris.size() < 12) {  // slivers: long axis ~1, width 1e-2 .. 1e-4, anywhere in [-8, 8]^3
        Vector3f c(uniform(-8, 8), uniform(-8, 8), uniform(-8, 8)), a(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)),
            b(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
        float w = std::pow(10.0f, uniform(-4, -2));
        tris.push_back({Point3f(c), Point3f(c + a), Point3f(c + a + w * b)});
    }
    while (tris.size() < 16) {
        Vector3f c(uniform(-8, 8), uniform(-8, 8), uniform(-8, 8));
        tris.push_back({Point3f(c), Point3f(c + Vector3f(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2))),
                        Point3f(c + Vector3f(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2)))});
    }
    return tris;
}

/// One leaf of \p tris (at most 16) for intersector \p kind.
TriangleStore leafOf(Intersector kind, const std::vector<std::array<Point3f, 3>> &tris) {
    std::vector<uint32_t> ids(tris.size());
    for (uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
    TriangleStore store;
    store.reset(kind, TriangleStore::leafWords(uint32_t(ids.size())));
    store.setLeaf(0, ids.data(), uint32_t(ids.size()), tris);
    return store;
}

// The shapes behind the faults, at random: one leaf of huge quads (axis-aligned and tilted),
// slivers (1:100 to 1:10^4) and ordinary triangles, hit by rays from origins near the world
// origin aimed at random points of them, and by rays leaving the ground from just above it. Every hit a kernel reports,
// at every lane width (bit-identical to one lane), whose exact crossing lies inside the
// triangle (not within 1e-6 of an edge: there the decision tests rule), lies within the
// oracle's eps of the exact plane: |t - t*| sin(angle) |d| <= 2^-17 max(|o|_inf, t |d|), which
// covers a spawned ray leaving the ground and finding it again (t* < 0).
TEST(KernelPrecision, HitPointsLieOnTheExactPlaneAtEveryWidth) {
    pcg32 rng(20261122);
    auto uniform = [&](float a, float b) { return a + (b - a) * float(rng() >> 8) * 0x1p-24f; };
    std::vector<std::array<Point3f, 3>> tris = hardTriangles(uniform);
    for (Intersector kind : {Intersector::Watertight, Intersector::MT}) {
        const TriangleStore store = leafOf(kind, tris);
        size_t hits[3] = {0, 0, 0}, bad = 0, differ = 0;
        for (int k = 0; k < 40000; ++k) {
            Point3f o(uniform(-10, 10), uniform(-10, 10), uniform(-10, 10));
            if (k % 2) o.y() = std::ldexp(uniform(0.5f, 1.0f), -int(rng() % 20));  // just above the ground
            Vector3f d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
            if (k % 4 == 1) {
                d.y() = std::abs(d.y());  // leaving the ground
            } else if (k % 4 != 3) {    // aimed at a random point of a random triangle
                const auto &p = tris[rng() % 16];
                float b1 = uniform(0, 1), b2 = uniform(0, 1);
                if (b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
                d = (p[0] + b1 * (p[1] - p[0]) + b2 * (p[2] - p[0])) - o;
            }
            if (d.isZero()) continue;
            const Ray3f ray(o, d);
            const TriangleRay tr(ray);
            TriangleStore::ChunkAnswers ref;
            store.chunkAnswers(1, tr, 0, 16, 0, ray.maxt, ref);
            for (int width : TriangleStore::laneWidths()) {
                TriangleStore::ChunkAnswers ans;
                store.chunkAnswers(width, tr, 0, 16, 0, ray.maxt, ans);
                bool same = ans.hits == ref.hits;
                for (int s = 0; s < 16; ++s)
                    if ((ref.hits >> s) & 1u) same = same && sameBits(ans.t[s], ref.t[s]);
                differ += !same;
            }
            const double dn = ray.d.cast<double>().norm(), oInf = ray.o.cast<double>().cwiseAbs().maxCoeff();
            for (int s = 0; s < 16; ++s) {
                if (!((ref.hits >> s) & 1u)) continue;
                double sinAngle, minBary, exact = exactPlaneT(tris[size_t(s)], ray, sinAngle, minBary);
                if (minBary < 1e-6) continue;  // near or beyond an edge: a question of the decision
                ++hits[s < 4 ? 0 : s < 12 ? 1 : 2];
                double apart = std::abs(double(ref.t[s]) - exact) * sinAngle * dn;
                if (apart > 0x1p-17 * std::max(oInf, double(ref.t[s]) * dn) && ++bad <= 5)
                    ADD_FAILURE() << intersectorName(kind) << " triangle " << s << ": t " << ref.t[s] << ", exact " << exact
                                  << ", hit point " << apart << " off the plane; o " << o.transpose() << " d " << d.transpose();
            }
        }
        EXPECT_EQ(bad, 0u) << intersectorName(kind);
        EXPECT_EQ(differ, 0u) << intersectorName(kind) << ": widths differ from 1 lane";
        EXPECT_GT(hits[0], 10000u) << intersectorName(kind) << " large triangles";
        EXPECT_GT(hits[1], 50u) << intersectorName(kind) << " slivers";
        EXPECT_GT(hits[2], 500u) << intersectorName(kind) << " ordinary triangles";
    }
}

/// Smallest barycentric coordinate, in long double, of the crossing of \p ray with the plane of
/// \p p (relative to the triangle: 0 on an edge, negative outside); NaN when the ray is parallel.
long double crossingMinBary(const std::array<Point3f, 3> &p, const Ray3f &ray) {
    using V = Eigen::Matrix<long double, 3, 1>;
    const V a = p[0].cast<long double>(), b = p[1].cast<long double>(), c = p[2].cast<long double>();
    const V o = ray.o.cast<long double>(), d = ray.d.cast<long double>(), n = (b - a).cross(c - a);
    const V x = o + (n.dot(a - o) / n.dot(d)) * d;
    const V q[3] = {a, b, c};
    long double m = 1.0L;
    for (int k = 0; k < 3; ++k) m = std::min(m, (q[(k + 1) % 3] - q[k]).cross(x - q[k]).dot(n) / n.squaredNorm());
    return m;
}

// Where the kernel recomputes t in double (exactPlaneT) it skips the double inside test when its
// own barycentrics clear a bound on their rounding error. That is sound only if every such
// crossing lies inside the triangle: checked in long double, at every width, on rays aimed at
// points 1e-9 .. 1e-2 (relative) inside and outside the edges of huge quads, slivers and
// ordinary triangles (where the float edge tests let crossings just outside through, which a
// bound too small would wrongly take as inside), and at interior points.
TEST(KernelPrecision, InsideTestIsSkippedOnlyWhereTheCrossingIsInside) {
    pcg32 rng(20261123);
    auto uniform = [&](float a, float b) { return a + (b - a) * float(rng() >> 8) * 0x1p-24f; };
    std::vector<std::array<Point3f, 3>> tris = hardTriangles(uniform);
    for (Intersector kind : {Intersector::Watertight, Intersector::MT}) {
        const TriangleStore store = leafOf(kind, tris);
        size_t known = 0, wrong = 0, outsideHits = 0;
        for (int k = 0; k < 60000; ++k) {
            Point3f o(uniform(-10, 10), uniform(-10, 10), uniform(-10, 10));
            if (k % 2) o.y() = std::ldexp(uniform(0.5f, 1.0f), -int(rng() % 12));  // just above the ground
            const auto &p = tris[rng() % 16];
            Vector3f target;
            if (k % 3 == 0) {  // an interior point
                float b1 = uniform(0, 1), b2 = uniform(0, 1);
                if (b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
                target = p[0] + b1 * (p[1] - p[0]) + b2 * (p[2] - p[0]);
            } else {  // beside a point of an edge, across it, by 1e-9 .. 1e-2 of the opposite corner's distance
                const int e = int(rng() % 3);
                const Vector3f a = p[size_t(e)], b = p[size_t(e + 1) % 3], c = p[size_t(e + 2) % 3];
                const Vector3f onEdge = a + uniform(0, 1) * (b - a);
                const float off = std::pow(10.0f, uniform(-9, -2)) * (rng() % 2 ? 1.0f : -1.0f);
                target = onEdge + off * (c - onEdge);
            }
            const Vector3f d = target - o;
            if (d.isZero()) continue;
            const Ray3f ray(o, d);
            for (int width : TriangleStore::laneWidths()) {
                TriangleStore::ChunkAnswers ans;
                store.chunkAnswers(width, TriangleRay(ray), 0, 16, 0, ray.maxt, ans);
                for (int s = 0; s < 16; ++s) {
                    const bool hit = (ans.hits >> s) & 1u, isKnown = (ans.insideKnown >> s) & 1u;
                    const long double m = crossingMinBary(tris[size_t(s)], ray);
                    if (width == 1) known += isKnown, outsideHits += hit && m < 0.0L;
                    if (isKnown && !(m > 0.0L) && ++wrong <= 5)
                        ADD_FAILURE() << intersectorName(kind) << ", " << width << " lanes, triangle " << s
                                      << ": inside test skipped, but the crossing's smallest barycentric is "
                                      << double(m) << "; o " << o.transpose() << " d " << d.transpose();
                }
            }
        }
        std::printf("[ inside   ] %-10s %zu exact-t lanes skipped the inside test; %zu hits cross just outside\n",
                    intersectorName(kind), known, outsideHits);
        EXPECT_EQ(wrong, 0u) << intersectorName(kind);
        EXPECT_GT(known, 10000u) << intersectorName(kind);   // the skip is taken
        EXPECT_GT(outsideHits, 100u) << intersectorName(kind);  // and the rays reach where it must not be
    }
}

} // namespace
