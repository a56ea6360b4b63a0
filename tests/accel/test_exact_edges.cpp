/// \file test_exact_edges.cpp
/// \brief The exact predicates behind the watertight kernel's hard cases, against integer
/// arithmetic written here (exact_triangle.h's scaled floats):
///  - exactlyCollinear / triangleCanBeHit, which decide which triangles the accelerators leave
///    out (corners on one line: no ray can hit them);
///  - exactEdgeVolumes' signs on the rays that make its double evaluation end at zero terms
///    (rays from a corner, axis-aligned rays through a corner).
/// The inputs mix scales from 2^-60 to 2^60 and offsets far from the origin, so that the
/// differences of corners round in double and the integer fallbacks run.
#include "exact_triangle.h"

#include <accel/exact_edges.h>
#include <accel/triangle.h>
#include <gtest/gtest.h>
#include <pcg_random.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

using namespace nori;

namespace {

using exact::Int;

/// (p1 - p0) x (p2 - p0) == 0, in exact integers.
bool collinearExactly(const std::array<Point3f, 3> &p) {
    Int a[3], b[3];
    for (int k = 0; k < 3; ++k) {
        a[k] = exact::scaled(p[1][k]) - exact::scaled(p[0][k]);
        b[k] = exact::scaled(p[2][k]) - exact::scaled(p[0][k]);
    }
    return a[1] * b[2] == a[2] * b[1] && a[2] * b[0] == a[0] * b[2] && a[0] * b[1] == a[1] * b[0];
}

/// Sign of d . ((q - o) x (r - o)), in exact integers.
int volumeSign(const Point3f &o, const Vector3f &d, const Point3f &q, const Point3f &r) {
    Int b[3], c[3], ds[3];
    for (int k = 0; k < 3; ++k) {
        b[k] = exact::scaled(q[k]) - exact::scaled(o[k]);
        c[k] = exact::scaled(r[k]) - exact::scaled(o[k]);
        ds[k] = exact::scaled(d[k]);
    }
    const Int v = ds[0] * (b[1] * c[2] - b[2] * c[1]) + ds[1] * (b[2] * c[0] - b[0] * c[2]) + ds[2] * (b[0] * c[1] - b[1] * c[0]);
    return v.sign();
}

void toRows(const std::array<Point3f, 3> &p, float rows[3][3]) {
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) rows[c][k] = p[c][k];
}

struct Sampler {
    pcg32 rng{2026};
    float uniform(float lo, float hi) { return lo + (hi - lo) * float(rng() >> 8) * 0x1p-24f; }
    /// A random point at scale 2^e (e in [-60, 60]) around \p centre.
    Point3f point(const Point3f &centre, int e) {
        return centre + std::ldexp(1.0f, e) * Point3f(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    }
    int scale() { return int(rng(121)) - 60; }
    Point3f centre() {
        switch (rng(3)) {
        case 0: return Point3f(0, 0, 0);
        case 1: return Point3f(1e6f, -3e5f, 7e6f);  // far from the origin: corners on a coarse grid
        default: return std::ldexp(1.0f, scale()) * Point3f(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
        }
    }
};

} // namespace

TEST(ExactEdges, CollinearCornersAreDecidedExactly) {
    Sampler s;
    size_t collinear = 0, separate = 0, oneUlp = 0;
    for (int i = 0; i < 60000; ++i) {
        const Point3f c = s.centre();
        const Point3f p0 = s.point(c, s.scale());
        Point3f p1 = s.point(c, s.scale()), p2;
        switch (i % 6) {
        case 0: p1 = p0; p2 = s.point(c, s.scale()); break;  // a segment (two corners coincide)
        case 1: p2 = p1; break;
        case 2: p1 = p2 = p0; break;  // a point
        case 3: p2 = p0 + 2.0f * (p1 - p0); break;  // on the line, up to float rounding
        case 4: p2 = 0.5f * (p0 + p1); break;
        default: p2 = p0 + 0.25f * (p1 - p0); break;
        }
        if (i % 12 >= 6) {  // one ulp off the line (where the corners lay on it), in one coordinate
            const int axis = int(s.rng(3));
            p2[axis] = std::nextafter(p2[axis], std::numeric_limits<float>::infinity());
            ++oneUlp;
        }
        const std::array<Point3f, 3> p{p0, p1, p2};
        float rows[3][3];
        toRows(p, rows);
        const bool expected = collinearExactly(p);
        // Each corner order: the answer belongs to the triangle, not to its first corner.
        for (int r = 0; r < 3; ++r) {
            const std::array<Point3f, 3> q{p[r], p[(r + 1) % 3], p[(r + 2) % 3]};
            float qr[3][3];
            toRows(q, qr);
            ASSERT_EQ(exactlyCollinear(qr), expected) << "corners " << q[0].transpose() << " | " << q[1].transpose() << " | "
                                                      << q[2].transpose();
            ASSERT_EQ(triangleCanBeHit(q), !expected);
        }
        (expected ? collinear : separate)++;
    }
    std::printf("[ collinear] %zu collinear, %zu not (of them %zu moved one ulp)\n", collinear, separate, oneUlp);
    // Both answers must be common, with many exactly collinear corners that are distinct.
    EXPECT_GT(collinear, 25000u);
    EXPECT_GT(separate, 15000u);
}

TEST(ExactEdges, ATriangleWithACornerNotFiniteCannotBeHit) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(triangleCanBeHit({Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0)}));
    EXPECT_FALSE(triangleCanBeHit({Point3f(0, 0, 0), Point3f(inf, 0, 0), Point3f(0, 1, 0)}));
    EXPECT_FALSE(triangleCanBeHit({Point3f(0, 0, nan), Point3f(1, 0, 0), Point3f(0, 1, 0)}));
}

TEST(ExactEdges, VolumesFromCornersAndAlongAxesHaveExactSigns) {
    Sampler s;
    size_t zeros = 0, checked = 0;
    for (int i = 0; i < 20000; ++i) {
        const Point3f c = s.centre();
        const int e = s.scale();
        std::array<Point3f, 3> p{s.point(c, e), s.point(c, e), s.point(c, e)};
        Point3f o;
        Vector3f d(s.uniform(-1, 1), s.uniform(-1, 1), s.uniform(-1, 1));
        if (i % 2 == 0) {
            o = p[i % 3];  // from a corner: two volumes are exactly zero
        } else {
            // Along an axis, exactly through a corner: one volume's terms are all zero.
            const int axis = int(s.rng(3));
            d = Vector3f::Zero();
            d[axis] = (s.rng(2) ? 1.0f : -1.0f) * std::ldexp(1.0f, s.scale() / 4);
            o = p[(i / 2) % 3];
            o[axis] -= d[axis] * 3.0f;
        }
        float rows[3][3], of[3] = {o.x(), o.y(), o.z()}, df[3] = {d.x(), d.y(), d.z()};
        toRows(p, rows);
        double vol[3];
        ASSERT_TRUE(exactEdgeVolumes(of, df, rows, vol));
        for (int k = 0; k < 3; ++k) {
            const int expected = volumeSign(o, d, p[(k + 1) % 3], p[(k + 2) % 3]);
            const int got = (vol[k] > 0) - (vol[k] < 0);
            ASSERT_EQ(got, expected) << "volume " << k << " o=" << o.transpose() << " d=" << d.transpose();
            zeros += expected == 0;
            ++checked;
        }
    }
    std::printf("[ volumes  ] %zu signs, %zu of them exactly zero\n", checked, zeros);
    EXPECT_GT(zeros, 15000u);
}
