/// \file triangle_box.cpp
/// \brief Separating-axis triangle/box test after Akenine-Möller 2001 (own implementation).
#include "triangle_box.h"
#include <cmath>

namespace nori {

namespace {
using V3 = Eigen::Vector3d;

/// Is \p axis separating: the triangle's projection (of the centred corners) lies entirely
/// outside the box's projection radius?
inline bool separates(const V3 &axis, const V3 &v0, const V3 &v1, const V3 &v2, const V3 &half) {
    double p0 = axis.dot(v0), p1 = axis.dot(v1), p2 = axis.dot(v2);
    double lo = std::min(p0, std::min(p1, p2)), hi = std::max(p0, std::max(p1, p2));
    double r = half.x() * std::abs(axis.x()) + half.y() * std::abs(axis.y()) + half.z() * std::abs(axis.z());
    return lo > r || hi < -r;
}
} // namespace

bool triangleOverlapsBox(const Point3f &a, const Point3f &b, const Point3f &c, const BoundingBox3f &box) {
    V3 center = 0.5 * (box.min.cast<double>() + box.max.cast<double>());
    V3 half = 0.5 * (box.max.cast<double>() - box.min.cast<double>());
    half += half.cwiseAbs().maxCoeff() * 0x1p-20 * V3::Ones() + V3::Constant(1e-30);
    V3 v0 = a.cast<double>() - center, v1 = b.cast<double>() - center, v2 = c.cast<double>() - center;

    // 1. The box's face normals: the bounding boxes must overlap.
    for (int i = 0; i < 3; ++i) {
        double lo = std::min(v0[i], std::min(v1[i], v2[i])), hi = std::max(v0[i], std::max(v1[i], v2[i]));
        if (lo > half[i] || hi < -half[i]) return false;
    }
    // 2. The nine cross products of triangle edges and box axes.
    const V3 edges[3] = {v1 - v0, v2 - v1, v0 - v2};
    for (const V3 &e : edges)
        for (int i = 0; i < 3; ++i) {
            V3 axis = V3::Unit(i).cross(e);
            if (separates(axis, v0, v1, v2, half)) return false;
        }
    // 3. The triangle's plane: the box must have corners on both sides (or touch it).
    V3 n = edges[0].cross(edges[1]);
    double d = n.dot(v0);
    double r = half.x() * std::abs(n.x()) + half.y() * std::abs(n.y()) + half.z() * std::abs(n.z());
    return std::abs(d) <= r;
}

} // namespace nori
