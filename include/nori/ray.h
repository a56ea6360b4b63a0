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

} // namespace nori
