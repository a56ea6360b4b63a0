/// \file triangle_box.cpp
/// \brief Separating-axis triangle/box test after Akenine-Möller 2001 (own implementation).
#include "triangle_box.h"
#include <cmath>
#include <cstdint>
#include <utility>

namespace nori {

namespace {
using V3 = Eigen::Vector3d;

/// Is the axis (a, b) in the coordinates (u, v) (its third component is zero) separating: the
/// triangle's projection (of the centred corners) lies entirely outside the box's projection
/// radius?
inline bool separates2(double a, double b, double u0, double v0, double u1, double v1, double u2, double v2, double hu,
                       double hv) {
    double p0 = a * u0 + b * v0, p1 = a * u1 + b * v1, p2 = a * u2 + b * v2;
    double lo = std::min(p0, std::min(p1, p2)), hi = std::max(p0, std::max(p1, p2));
    double r = hu * std::abs(a) + hv * std::abs(b);
    return lo > r || hi < -r;
}
} // namespace

bool triangleOverlapsBox(const Point3f &a, const Point3f &b, const Point3f &c, const BoundingBox3f &box) {
    return triangleOverlapsBox(a, b, c, box, axisAlignedPlane(a, b, c));
}

bool triangleOverlapsBox(const Point3f &a, const Point3f &b, const Point3f &c, const BoundingBox3f &box, int plane) {
    V3 center = 0.5 * (box.min.cast<double>() + box.max.cast<double>());
    V3 half = 0.5 * (box.max.cast<double>() - box.min.cast<double>());
    half += half.cwiseAbs().maxCoeff() * 0x1p-20 * V3::Ones() + V3::Constant(1e-30);
    V3 v0 = a.cast<double>() - center, v1 = b.cast<double>() - center, v2 = c.cast<double>() - center;

    // 1. The box's face normals: the bounding boxes must overlap.
    for (int i = 0; i < 3; ++i) {
        double lo = std::min(v0[i], std::min(v1[i], v2[i])), hi = std::max(v0[i], std::max(v1[i], v2[i]));
        if (lo > half[i] || hi < -half[i]) return false;
    }
    const V3 edges[3] = {v1 - v0, v2 - v1, v0 - v2};
    // Is unit(i) x e, for a triangle edge e, a separating axis? Each such axis has a zero
    // component, so each projection is a two-term dot product: written out, this is about a
    // third of the build's time on scenes of long thin triangles.
    auto edgeSeparates = [&](int i, const V3 &e) {
        switch (i) {
        case 0: return separates2(-e.z(), e.y(), v0.y(), v0.z(), v1.y(), v1.z(), v2.y(), v2.z(), half.y(), half.z());  // (0, -e.z, e.y)
        case 1: return separates2(e.z(), -e.x(), v0.x(), v0.z(), v1.x(), v1.z(), v2.x(), v2.z(), half.x(), half.z());  // (e.z, 0, -e.x)
        default: return separates2(-e.y(), e.x(), v0.x(), v0.y(), v1.x(), v1.y(), v2.x(), v2.y(), half.x(), half.y());  // (-e.y, e.x, 0)
        }
    };
    // A triangle in an axis-aligned plane x_i = const (i = \p plane: a wall, a floor, a box's
    // face, most of a room's or a city's triangles) needs only the three edge axes unit(i) x e,
    // which lie in its plane. Its edges' i components are differences of equal coordinates,
    // exactly zero, so its normal and the six other edge axes are unit(i) times a factor: their
    // tests compare the factor times the corners' common x_i with the factor times half[i],
    // which (1.) has compared unscaled, and scaling both sides by the same double never
    // reverses a comparison. The same answer as the general test below, from a third of its axes.
    if (plane >= 0) {
        for (const V3 &e : edges)
            if (edgeSeparates(plane, e)) return false;
        return true;
    }
    // 2. The triangle's plane: the box must have corners on both sides (or touch it). Tested
    // before the edge axes (the answer is the same whichever axis separates): a nearly flat
    // triangle beside a cell above or below it is separated here.
    {
        V3 n = edges[0].cross(edges[1]);
        double d = n.dot(v0);
        double r = half.x() * std::abs(n.x()) + half.y() * std::abs(n.y()) + half.z() * std::abs(n.z());
        if (!(std::abs(d) <= r)) return false;
    }
    // 3. The nine cross products of triangle edges and box axes, unit(i) x e, in lanes: one
    // vector per box axis i, one lane per edge (the fourth repeats the first), without a branch
    // per axis. A triangle off the axes (a turned wall, a scanned mesh) touches about half the
    // cells it is tested against (turned towers: 35,686 of 74,022), and then every axis has to
    // be computed anyway; axis by axis, the branches mispredicted.
    typedef double D4 __attribute__((vector_size(32)));
    typedef int64_t M4 __attribute__((vector_size(32)));
    // (Lanes of corners, then edges as differences: a vector built with zero lanes compiled to
    // a move that valgrind cannot decode, and callgrind is how the build is measured.)
    auto lanes = [&](int a) {
        return std::pair<D4, D4>{D4{v0[a], v1[a], v2[a], v0[a]}, D4{v1[a], v2[a], v0[a], v1[a]}};
    };
    const auto [x0, x1] = lanes(0);
    const auto [y0, y1] = lanes(1);
    const auto [z0, z1] = lanes(2);
    const D4 ex = x1 - x0, ey = y1 - y0, ez = z1 - z0;  // edges[j] in lane j
    auto abs4 = [](D4 v) { return v < 0.0 ? -v : v; };
    // Axis (a, b) in the coordinates (u, v) of the plane across box axis i, corners' (u, v) in
    // lanes per corner: separating where the triangle's projection lies outside the box's.
    M4 outside = {};
    auto test = [&](D4 a, D4 b, int u, int v) {
        const D4 p0 = a * v0[u] + b * v0[v], p1 = a * v1[u] + b * v1[v], p2 = a * v2[u] + b * v2[v];
        const D4 lo = p0 < p1 ? (p0 < p2 ? p0 : p2) : (p1 < p2 ? p1 : p2);
        const D4 hi = p0 > p1 ? (p0 > p2 ? p0 : p2) : (p1 > p2 ? p1 : p2);
        const D4 r = half[u] * abs4(a) + half[v] * abs4(b);
        outside |= (lo > r) | (hi < -r);
    };
    test(-ez, ey, 1, 2);  // unit(x) x e = (0, -e.z, e.y)
    test(ez, -ex, 0, 2);  // unit(y) x e = (e.z, 0, -e.x)
    test(-ey, ex, 0, 1);  // unit(z) x e = (-e.y, e.x, 0)
    const bool separated = (outside[0] | outside[1] | outside[2] | outside[3]) != 0;
    return !separated;
}

} // namespace nori
