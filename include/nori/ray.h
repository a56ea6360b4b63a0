/// \file ray.h
/// \brief A ray segment o + t d, t in [mint, maxt].
#pragma once

#include <nori/common.h>

namespace nori {

/// \brief Ray with a cached reciprocal direction for slab tests.
struct Ray3f {
    Point3f o;      ///< origin
    Vector3f d;     ///< direction (need not be normalised)
    Vector3f dRcp;  ///< component-wise 1/d (±inf for zero components)
    float mint = 0.0f;
    float maxt = Infinity;

    Ray3f() = default;
    Ray3f(const Point3f &o, const Vector3f &d, float mint = 0.0f, float maxt = Infinity)
        : o(o), d(d), mint(mint), maxt(maxt) { update(); }

    /// \brief Recompute dRcp after changing d.
    void update() { dRcp = d.cwiseInverse(); }

    /// \brief The point at parameter t.
    Point3f operator()(float t) const { return o + t * d; }
};

/// \brief Move a surface point off its surface, to the side of \p n that \p d points into,
/// so that a ray spawned there does not hit the surface it starts on. The offset is
/// relative to the point's magnitude: a hit point computed in float carries an absolute
/// error of a few ulps of its largest coordinate (cf. pbrt-v4, "Robust spawned rays"),
/// and 2^-18 relative is ~30x that bound while staying far below any sane triangle size.
inline Point3f offsetRayOrigin(const Point3f &p, const Normal3f &n, const Vector3f &d) {
    float scale = p.cwiseAbs().maxCoeff();
    float offset = scale * 0x1p-18f + 0x1p-100f;
    return p + (n.dot(d) >= 0.0f ? offset : -offset) * n;
}

} // namespace nori
