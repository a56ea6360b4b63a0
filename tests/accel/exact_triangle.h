/// \file exact_triangle.h
/// \brief Exact-arithmetic answers to "does this ray hit this triangle?" for the decision tests:
/// integers (Boost.Multiprecision) instead of floating point, so that the expected answer owes
/// nothing to the kernels under test.
///
/// Every finite float is an integer multiple of 2^-149, so x * 2^149 is an integer (at most
/// 2^277); sums and products of such integers are exact in 1024 bits, and only signs (and, for
/// the margins, ratios rounded to double at the very end) are read from them.
#pragma once

#include <nori/ray.h>
#include <boost/multiprecision/cpp_int.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace nori::exact {

using Int = boost::multiprecision::int1024_t;

/// x * 2^149 as an exact integer (x finite).
inline Int scaled(float x) {
    int e;
    const float m = std::frexp(x, &e);                            // x = m 2^e, 0.5 <= |m| < 1
    const auto mant = static_cast<int64_t>(std::ldexp(m, 24));  // exact: 24 significant bits
    const int shift = e - 24 + 149;
    Int r = mant;
    return shift >= 0 ? Int(r << shift) : Int(r / (Int(1) << -shift));  // subnormals: low bits are zero
}

inline int sign(const Int &x) { return x.sign(); }
inline double toDouble(const Int &x) { return x.convert_to<double>(); }

// ---------------------------------------------------------------------------------------------
// The watertight contract (Woop, Benthin & Wald 2013, JCGT 2(1)): the ray setup and the shear of
// each corner are rounded floating-point operations *by the algorithm's definition* (that is
// what makes two triangles sharing a corner see the same sheared corner); the edge functions
// must then have their exact signs. Recomputed here from the paper, not from the kernel.

struct Shear {
    int kx, ky, kz;
    float sx, sy, sz;
};

/// Section 3 of the paper: kz is the dominant axis of d (first of equal ones as max_dim picks
/// it: x over y over z only when strictly larger), kx, ky the next two, swapped when d[kz] < 0.
inline Shear shearOf(const Vector3f &d) {
    const float ax = std::abs(d.x()), ay = std::abs(d.y()), az = std::abs(d.z());
    Shear s;
    s.kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    s.kx = (s.kz + 1) % 3;
    s.ky = (s.kx + 1) % 3;
    if (d[s.kz] < 0.0f) std::swap(s.kx, s.ky);
    s.sx = d[s.kx] / d[s.kz];
    s.sy = d[s.ky] / d[s.kz];
    s.sz = 1.0f / d[s.kz];
    return s;
}

/// One corner relative to the origin and sheared, in float (this file is compiled without FMA
/// contraction, as the kernel is): x, y and the unsheared depth z.
inline std::array<float, 3> shearedCorner(const Shear &s, const Point3f &o, const Point3f &p) {
    const float z = p[s.kz] - o[s.kz];
    const float x = (p[s.kx] - o[s.kx]) - s.sx * z;
    const float y = (p[s.ky] - o[s.ky]) - s.sy * z;
    return {x, y, z};
}

/// Exact a.x * b.y - a.y * b.x of two sheared corners (an edge function).
inline Int edgeFunction(const std::array<float, 3> &a, const std::array<float, 3> &b) {
    return scaled(a[0]) * scaled(b[1]) - scaled(a[1]) * scaled(b[0]);
}

/// Float a.x * b.y - a.y * b.x, as the kernel's first (single precision) attempt computes it.
inline float edgeFunctionFloat(const std::array<float, 3> &a, const std::array<float, 3> &b) {
    return a[0] * b[1] - a[1] * b[0];
}

struct WatertightAnswer {
    bool hit = false;        ///< edge signs not mixed, not all zero, and t in [mint, maxt]
    bool tBoundary = false;  ///< t within a relative 1e-4 of mint or maxt: the decision is left open
    int edgeSign[3] = {0, 0, 0};  ///< exact signs of U (edge p1 p2), V (edge p2 p0), W (edge p0 p1)
    bool rescued = false;  ///< some float edge function is 0 while its exact value is not
    double t = 0.0;        ///< exact t of the plane crossing, rounded to double
};

inline WatertightAnswer watertight(const Ray3f &ray, const Point3f &p0, const Point3f &p1, const Point3f &p2) {
    const Shear s = shearOf(ray.d);
    const auto a = shearedCorner(s, ray.o, p0), b = shearedCorner(s, ray.o, p1), c = shearedCorner(s, ray.o, p2);
    const Int U = edgeFunction(c, b), V = edgeFunction(a, c), W = edgeFunction(b, a);
    WatertightAnswer r;
    r.edgeSign[0] = sign(U), r.edgeSign[1] = sign(V), r.edgeSign[2] = sign(W);
    r.rescued = (edgeFunctionFloat(c, b) == 0.0f && sign(U) != 0) || (edgeFunctionFloat(a, c) == 0.0f && sign(V) != 0) ||
                (edgeFunctionFloat(b, a) == 0.0f && sign(W) != 0);
    const bool anyNeg = sign(U) < 0 || sign(V) < 0 || sign(W) < 0, anyPos = sign(U) > 0 || sign(V) > 0 || sign(W) > 0;
    const Int det = U + V + W;
    if ((anyNeg && anyPos) || sign(det) == 0) return r;
    // t = sz (U az + V bz + W cz) / det, with the float sz and corner depths of the algorithm
    // (T carries one factor 2^149 more than det).
    const Int T = U * scaled(a[2]) + V * scaled(b[2]) + W * scaled(c[2]);
    r.t = toDouble(T) / toDouble(det) * std::ldexp(double(s.sz), -149);
    const double scale = std::max({std::abs(r.t), double(std::abs(ray.mint)), 1e-30});
    r.tBoundary = std::abs(r.t - ray.mint) <= 1e-4 * scale || (std::isfinite(ray.maxt) && std::abs(r.t - ray.maxt) <= 1e-4 * scale);
    r.hit = r.t >= ray.mint && r.t <= ray.maxt;
    return r;
}

// ---------------------------------------------------------------------------------------------
// Geometry: the real line o + t d against the real triangle, no rounding at all.

struct GeometricAnswer {
    bool hit = false;
    bool degenerate = false;  ///< ray parallel to the triangle's plane, or zero-area triangle
    /// min |b_i| / (|d| m^2) over the three triple products b_i = d . (corner x corner), m the
    /// longest corner - origin: 0 on an edge line, and in the units in which float rounding errs
    /// (both kernels evaluate such products with errors of a few ulps of |d| m^2).
    double margin = 0.0;
    double t = 0.0;
};

inline GeometricAnswer geometric(const Ray3f &ray, const Point3f &p0, const Point3f &p1, const Point3f &p2) {
    using V = std::array<Int, 3>;
    auto rel = [&](const Point3f &p) { return V{scaled(p.x()) - scaled(ray.o.x()), scaled(p.y()) - scaled(ray.o.y()), scaled(p.z()) - scaled(ray.o.z())}; };
    auto cross = [](const V &a, const V &b) { return V{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; };
    auto dot = [](const V &a, const V &b) { return Int(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]); };
    const V A = rel(p0), B = rel(p1), C = rel(p2), d{scaled(ray.d.x()), scaled(ray.d.y()), scaled(ray.d.z())};
    // Signed volumes d . (B x C) etc.: the barycentric weights of the line's crossing, up to scale.
    const Int b0 = dot(d, cross(B, C)), b1 = dot(d, cross(C, A)), b2 = dot(d, cross(A, B));
    const Int sum = b0 + b1 + b2;  // d . n with n = (B - A) x (C - A)
    GeometricAnswer g;
    if (sign(sum) == 0) {
        g.degenerate = true;
        return g;
    }
    double m = 0.0;
    for (const Point3f *p : {&p0, &p1, &p2}) m = std::max(m, (p->cast<double>() - ray.o.cast<double>()).norm());
    const double a0 = std::abs(toDouble(b0)), a1 = std::abs(toDouble(b1)), a2 = std::abs(toDouble(b2));
    g.margin = std::min({a0, a1, a2}) / (ray.d.cast<double>().norm() * m * m) * std::ldexp(1.0, -447);
    const bool mixed = (sign(b0) < 0 || sign(b1) < 0 || sign(b2) < 0) && (sign(b0) > 0 || sign(b1) > 0 || sign(b2) > 0);
    // t = (A . n) / (d . n); A . n = A . (B x C) (the other terms vanish).
    g.t = toDouble(dot(A, cross(B, C))) / toDouble(sum);
    g.hit = !mixed && g.t >= ray.mint && g.t <= ray.maxt;
    return g;
}

/// Exact sign of the edge volume d . ((a - o) x (b - o)): 0 exactly when the real line o + t d
/// meets the line through a and b (or is parallel to it).
inline int edgeVolumeSign(const Ray3f &ray, const Point3f &a, const Point3f &b) {
    using V = std::array<Int, 3>;
    auto rel = [&](const Point3f &p) { return V{scaled(p.x()) - scaled(ray.o.x()), scaled(p.y()) - scaled(ray.o.y()), scaled(p.z()) - scaled(ray.o.z())}; };
    const V A = rel(a), B = rel(b), d{scaled(ray.d.x()), scaled(ray.d.y()), scaled(ray.d.z())};
    return sign(Int(d[0] * (A[1] * B[2] - A[2] * B[1]) + d[1] * (A[2] * B[0] - A[0] * B[2]) + d[2] * (A[0] * B[1] - A[1] * B[0])));
}

} // namespace nori::exact
