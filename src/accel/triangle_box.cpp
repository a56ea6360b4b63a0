/// \file triangle_box.cpp
/// \brief Separating-axis triangle/box test after Akenine-Möller 2001 (own implementation).
#include "triangle_box.h"
#include <cmath>
#include <cstdint>

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
    return TriangleBoxTest(a, b, c, axisAlignedPlane(a, b, c)).overlaps(box);
}

bool triangleOverlapsBox(const Point3f &a, const Point3f &b, const Point3f &c, const BoundingBox3f &box, int plane) {
    return TriangleBoxTest(a, b, c, plane).overlaps(box);
}

TriangleBoxTest::TriangleBoxTest(const Point3f &a, const Point3f &b, const Point3f &c, int plane) : m_plane(plane) {
    const V3 v0 = a.cast<double>(), v1 = b.cast<double>(), v2 = c.cast<double>();
    for (int i = 0; i < 3; ++i) {
        m_v[0][i] = v0[i];
        m_v[1][i] = v1[i];
        m_v[2][i] = v2[i];
    }
    // Any axis that separates the projections separates the triangle from the box, so the
    // edges may come from the corners before they are centred on a box: only the projections'
    // rounding matters, and the box's growth covers it (triangleOverlapsBox).
    const V3 edges[3] = {v1 - v0, v2 - v1, v0 - v2};
    const V3 n = edges[0].cross(edges[1]);
    for (int j = 0; j < 3; ++j) {
        const V3 &e = edges[j];
        // (Zero lanes as a computed zero: vectors with literal zero lanes compiled to a move
        // that valgrind cannot decode, and callgrind is how the build is measured.)
        const double zero = e.x() - e.x();
        m_x[j] = D4{zero, e.z(), -e.y(), n.x()};
        m_y[j] = D4{-e.z(), zero, e.x(), n.y()};
        m_z[j] = D4{e.y(), -e.x(), zero, n.z()};
        m_ax[j] = m_x[j] < 0.0 ? -m_x[j] : m_x[j];
        m_ay[j] = m_y[j] < 0.0 ? -m_y[j] : m_y[j];
        m_az[j] = m_z[j] < 0.0 ? -m_z[j] : m_z[j];
    }
}

bool TriangleBoxTest::overlaps(const BoundingBox3f &box) const {
    V3 center = 0.5 * (box.min.cast<double>() + box.max.cast<double>());
    V3 half = 0.5 * (box.max.cast<double>() - box.min.cast<double>());
    half += half.cwiseAbs().maxCoeff() * 0x1p-20 * V3::Ones() + V3::Constant(1e-30);
    const V3 v0 = V3(m_v[0][0], m_v[0][1], m_v[0][2]) - center, v1 = V3(m_v[1][0], m_v[1][1], m_v[1][2]) - center,
             v2 = V3(m_v[2][0], m_v[2][1], m_v[2][2]) - center;

    // 1. The box's face normals: the bounding boxes must overlap.
    for (int i = 0; i < 3; ++i) {
        double lo = std::min(v0[i], std::min(v1[i], v2[i])), hi = std::max(v0[i], std::max(v1[i], v2[i]));
        if (lo > half[i] || hi < -half[i]) return false;
    }
    // A triangle in an axis-aligned plane x_i = const (i = m_plane: a wall, a floor, a box's
    // face, most of a room's or a city's triangles) needs only the three edge axes unit(i) x e,
    // which lie in its plane. Its edges' i components are differences of equal coordinates,
    // exactly zero, so its normal and the six other edge axes are unit(i) times a factor: their
    // tests compare the factor times the corners' common x_i with the factor times half[i],
    // which (1.) has compared unscaled, and scaling both sides by the same double never
    // reverses a comparison. The same answer as the general test below, from a third of its
    // axes. Is unit(i) x e a separating axis? Each such axis has a zero component, so each
    // projection is a two-term dot product (lane i of the axes below, whose third term is 0).
    if (m_plane >= 0) {
        const int i = m_plane;
        for (int j = 0; j < 3; ++j) {
            const bool separated =
                i == 0   ? separates2(m_y[j][0], m_z[j][0], v0.y(), v0.z(), v1.y(), v1.z(), v2.y(), v2.z(), half.y(), half.z())
                : i == 1 ? separates2(m_x[j][1], m_z[j][1], v0.x(), v0.z(), v1.x(), v1.z(), v2.x(), v2.z(), half.x(), half.z())
                         : separates2(m_x[j][2], m_y[j][2], v0.x(), v0.y(), v1.x(), v1.y(), v2.x(), v2.y(), half.x(), half.y());
            if (separated) return false;
        }
        return true;
    }
    // 2. and 3. The triangle's plane and the nine cross products of triangle edges and box
    // axes, ten axes in lanes at once, without a branch per axis: a triangle off the axes (a
    // turned wall, a scanned mesh) touches about half the cells it is tested against (turned
    // towers: 35,686 of 74,022), and then every axis has to be computed anyway. (Lane 3 tests
    // the normal three times: a repeated axis gives the same answer.)
    typedef int64_t M4 __attribute__((vector_size(32)));
    M4 outside = {};
    for (int j = 0; j < 3; ++j) {
        const D4 x = m_x[j], y = m_y[j], z = m_z[j];
        const D4 p0 = x * v0.x() + y * v0.y() + z * v0.z(), p1 = x * v1.x() + y * v1.y() + z * v1.z(),
                 p2 = x * v2.x() + y * v2.y() + z * v2.z();
        const D4 lo = p0 < p1 ? (p0 < p2 ? p0 : p2) : (p1 < p2 ? p1 : p2);
        const D4 hi = p0 > p1 ? (p0 > p2 ? p0 : p2) : (p1 > p2 ? p1 : p2);
        const D4 r = half.x() * m_ax[j] + half.y() * m_ay[j] + half.z() * m_az[j];
        outside |= (lo > r) | (hi < -r);
    }
    const bool separated = (outside[0] | outside[1] | outside[2] | outside[3]) != 0;
    return !separated;
}

} // namespace nori
