/// \file test_geometry.h
/// \brief Double-precision geometry used by the tests to judge disagreements between
/// intersectors (distances between rays, edges, points and triangles).
#pragma once

#include <nori/common.h>
#include <algorithm>

namespace nori {

using V3d = Eigen::Vector3d;

namespace {

// Not every test file uses every helper.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"

/// Closest points between segments [p0, p1] and [q0, q1]; returns the distance (double).
double segmentDistance(const V3d &p0, const V3d &p1, const V3d &q0, const V3d &q1) {
    V3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    double a = d1.dot(d1), e = d2.dot(d2), f = d2.dot(r);
    double s = 0.0, t = 0.0;
    if (a <= 0.0 && e <= 0.0) return r.norm();
    if (a <= 0.0) {
        t = std::clamp(f / e, 0.0, 1.0);
    } else {
        double c = d1.dot(r);
        if (e <= 0.0) {
            s = std::clamp(-c / a, 0.0, 1.0);
        } else {
            double b = d1.dot(d2), denom = a * e - b * b;
            s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
            t = (b * s + f) / e;
            if (t < 0.0) {
                t = 0.0;
                s = std::clamp(-c / a, 0.0, 1.0);
            } else if (t > 1.0) {
                t = 1.0;
                s = std::clamp((b - c) / a, 0.0, 1.0);
            }
        }
    }
    return ((p0 + s * d1) - (q0 + t * d2)).norm();
}

/// Distance from \p p to the triangle (a, b, c), all in double.
double pointTriangleDistance(const V3d &p, const V3d &a, const V3d &b, const V3d &c) {
    V3d n = (b - a).cross(c - a);
    double nn = n.squaredNorm();
    if (nn > 0.0) {
        // Inside the prism over the triangle: the distance to the plane.
        V3d q = p - n * (n.dot(p - a) / nn);
        bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                      (a - c).cross(q - c).dot(n) >= 0;
        if (inside) return (p - q).norm();
    }
    return std::min({segmentDistance(p, p, a, b), segmentDistance(p, p, b, c), segmentDistance(p, p, c, a)});
}

/// Does the segment [r0, r1] cross the triangle (a, b, c) at least \p eps away from its
/// boundary? (A robust hit: every correct intersector must report it.)
bool crossesInterior(const V3d &r0, const V3d &r1, const V3d &a, const V3d &b, const V3d &c, double eps) {
    V3d d = r1 - r0;
    double s0 = (b - a).cross(c - a).dot(r0 - a), s1 = (b - a).cross(c - a).dot(r1 - a);
    if (s0 * s1 > 0.0 || s0 == s1) return false;  // both ends on one side, or in the plane
    V3d p = r0 + d * (s0 / (s0 - s1));
    V3d n = (b - a).cross(c - a);
    bool inside = (b - a).cross(p - a).dot(n) > 0 && (c - b).cross(p - b).dot(n) > 0 && (a - c).cross(p - c).dot(n) > 0;
    return inside && segmentDistance(r0, r1, a, b) > eps && segmentDistance(r0, r1, b, c) > eps &&
           segmentDistance(r0, r1, c, a) > eps;
}

#pragma GCC diagnostic pop

} // namespace
} // namespace nori
