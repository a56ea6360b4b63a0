/// \file ray.h
/// \brief A ray segment o + t d, t in [mint, maxt], and robust spawning of rays from surfaces.
#pragma once

#include <nori/common.h>
#include <cmath>

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

/// \brief Unit roundoff of float arithmetic (round to nearest): fl(x op y) = (x op y)(1 + e), |e| <= u.
constexpr float UnitRoundoff = 0x1p-24f;

/// \brief gamma_n = n u / (1 - n u): bounds the relative error of n successive roundings (Higham 2002, 3.1).
constexpr float roundingBound(int n) { return float(n) * UnitRoundoff / (1.0f - float(n) * UnitRoundoff); }

/// \brief A shadow segment stops this fraction short of its end point: what the intersectors may
/// get wrong about a triangle at the far end of a long segment (see src/core/ray.cpp).
constexpr float ShadowEpsilon = 0x1p-12f;

/// \brief Per-component bound of the rounding error of p = b0 p0 + b1 p1 + b2 p2 computed in float
/// with b0 = 1 - b1 - b2 (derivation in src/core/ray.cpp).
Vector3f interpolationError(const Point3f &p0, const Point3f &p1, const Point3f &p2, float b0, float b1, float b2);

/// \brief How far along the unit geometric normal \p ng a ray leaving the point \p p of triangle
/// (p0, p1, p2) must start so that neither intersector finds that triangle (or a coplanar neighbour
/// of similar size) again; \p pError is interpolationError() of p. Derivation in src/core/ray.cpp.
float spawnOffset(const Point3f &p0, const Point3f &p1, const Point3f &p2, const Point3f &p, const Vector3f &pError,
                  const Normal3f &ng);
/// \brief spawnOffset() when the caller already has twice the triangle's area, |(p1 - p0) x (p2 - p0)|.
float spawnOffset(const Point3f &p0, const Point3f &p1, const Point3f &p2, const Point3f &p, const Vector3f &pError,
                  const Normal3f &ng, float twiceArea);

/// \brief Move the surface point \p p by \p offset along \p ng, to the side that \p d points into,
/// then one ulp further per component so that rounding the sum cannot give any distance back.
inline Point3f offsetRayOrigin(const Point3f &p, float offset, const Normal3f &ng, const Vector3f &d) {
    Vector3f shift = (ng.dot(d) >= 0.0f ? offset : -offset) * ng;
    Point3f o = p + shift;
    for (int k = 0; k < 3; ++k) {
        if (shift[k] > 0.0f) o[k] = std::nextafter(o[k], Infinity);
        else if (shift[k] < 0.0f) o[k] = std::nextafter(o[k], -Infinity);
    }
    return o;
}

/// \brief A ray leaving the surface point \p p (spawn offset \p offset, geometric normal \p ng)
/// along \p d, up to parameter \p maxt.
inline Ray3f spawnRay(const Point3f &p, float offset, const Normal3f &ng, const Vector3f &d, float maxt = Infinity) {
    return Ray3f(offsetRayOrigin(p, offset, ng, d), d, 0.0f, maxt);
}

/// \brief A shadow segment between two surface points: both ends are moved off their surfaces
/// towards each other and the segment stops ShadowEpsilon short of the far end, so neither end's
/// triangle occludes it. Test it with an any-hit query on [0, maxt].
inline Ray3f spawnSegment(const Point3f &p, float offset, const Normal3f &ng, const Point3f &q, float qOffset,
                          const Normal3f &qng) {
    Point3f from = offsetRayOrigin(p, offset, ng, q - p);
    Point3f to = offsetRayOrigin(q, qOffset, qng, p - q);
    return Ray3f(from, to - from, 0.0f, 1.0f - ShadowEpsilon);
}

} // namespace nori
