/// \file exact_edges.cpp
/// \brief Exact edge volumes of a ray and a triangle: a double evaluation with a rounding error
/// bound, and exact integers where the bound does not settle the sign.
#include "exact_edges.h"
#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <cstdint>

namespace nori {

namespace {

// Every finite float is an integer multiple of 2^-149 below 2^128 in magnitude, so x 2^149 is an
// integer below 2^277; a difference of two is below 2^278 and a product of three such below 2^834:
// 1024 bits hold every edge volume exactly.
using Int = boost::multiprecision::int1024_t;

Int scaled(float x) {
    int e;
    const float m = std::frexp(x, &e);  // x = m 2^e, 0.5 <= |m| < 1
    const int64_t mant = int64_t(std::ldexp(m, 24));
    const int shift = e - 24 + 149;
    // A subnormal's mantissa has at least -shift trailing zero bits: the right shift is exact.
    return shift >= 0 ? Int(Int(mant) << shift) : Int(mant >> -shift);
}

/// d . (b x c) exactly, all three as scaled integers (the result carries the factor 2^447).
Int volume(const Int d[3], const Int b[3], const Int c[3]) {
    return d[0] * (b[1] * c[2] - b[2] * c[1]) + d[1] * (b[2] * c[0] - b[0] * c[2]) + d[2] * (b[0] * c[1] - b[1] * c[0]);
}

} // namespace

bool exactEdgeVolumes(const float o[3], const float d[3], const float p[3][3], double vol[3]) {
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(o[k]) || !std::isfinite(d[k]) || !std::isfinite(p[0][k]) || !std::isfinite(p[1][k]) ||
            !std::isfinite(p[2][k]))
            return false;
    // Corners relative to the origin in double: each difference of floats is exact unless their
    // exponents lie more than 29 apart, and then off by at most a relative 2^-53.
    double q[3][3];
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) q[c][k] = double(p[c][k]) - double(o[k]);
    const double dd[3] = {d[0], d[1], d[2]};
    bool settled[3];
    for (int e = 0; e < 3; ++e) {
        const double *b = q[(e + 1) % 3], *c = q[(e + 2) % 3];
        const double x = b[1] * c[2] - b[2] * c[1], y = b[2] * c[0] - b[0] * c[2], z = b[0] * c[1] - b[1] * c[0];
        vol[e] = dd[0] * x + dd[1] * y + dd[2] * z;
        // First-order rounding error: 2 for the differences, 1 for each product, 1 for the cross
        // product's difference, 1 for the product with d and 2 for the sum: at most 7 units of
        // 2^-53 of the sum of the terms' magnitudes (which cannot underflow or overflow: floats
        // lie within 2^-149 .. 2^128, products of three within double's range). 2^-49 = 16
        // units leaves room for the rounding of the bound itself.
        const double terms = std::abs(dd[0]) * (std::abs(b[1] * c[2]) + std::abs(b[2] * c[1])) +
                             std::abs(dd[1]) * (std::abs(b[2] * c[0]) + std::abs(b[0] * c[2])) +
                             std::abs(dd[2]) * (std::abs(b[0] * c[1]) + std::abs(b[1] * c[0]));
        // All terms zero: each has a factor that is exactly zero (a difference of floats is
        // zero only when they are equal, and no product of nonzero ones underflows), so the
        // volume is exactly zero (a ray from a corner, as a shadow ray from a vertex is).
        settled[e] = std::abs(vol[e]) > 0x1p-49 * terms || terms == 0.0;
    }
    if (settled[0] && settled[1] && settled[2]) return true;
    // Within rounding of an edge line (or the ray in the plane): exact integers.
    Int ds[3], qs[3][3];
    for (int k = 0; k < 3; ++k) {
        ds[k] = scaled(d[k]);
        const Int ok = scaled(o[k]);
        for (int c = 0; c < 3; ++c) qs[c][k] = scaled(p[c][k]) - ok;
    }
    for (int e = 0; e < 3; ++e) {
        if (settled[e]) continue;
        const Int v = volume(ds, qs[(e + 1) % 3], qs[(e + 2) % 3]);
        // Rounded to double (a nonzero volume is at least 2^-447 of it: no underflow).
        vol[e] = v.is_zero() ? 0.0 : std::ldexp(v.convert_to<double>(), -447);
    }
    return true;
}

namespace {
/// The exact test of exactlyCollinear where the double evaluation leaves it open (out of line:
/// its integers' stack frame would otherwise be set up on every call).
[[gnu::noinline]] bool collinearInIntegers(const float p[3][3]) {
    Int sa[3], sb[3];
    for (int k = 0; k < 3; ++k) {
        const Int p0 = scaled(p[0][k]);
        sa[k] = scaled(p[1][k]) - p0;
        sb[k] = scaled(p[2][k]) - p0;
    }
    for (int e = 0; e < 3; ++e) {
        const int i = (e + 1) % 3, j = (e + 2) % 3;
        if (sa[i] * sb[j] != sa[j] * sb[i]) return false;
    }
    return true;
}
} // namespace

bool exactlyCollinear(const float p[3][3]) {
    // Two corners that coincide (a point or a segment: common where float rounding has merged
    // the corners of small triangles far from the origin).
    auto same = [&](int i, int j) { return p[i][0] == p[j][0] && p[i][1] == p[j][1] && p[i][2] == p[j][2]; };
    if (same(0, 1) || same(0, 2) || same(1, 2)) return true;
    // Edge vectors in double: each difference within a relative 2^-53 (exact unless the
    // exponents lie more than 29 apart); each cross product component then within 4 units of
    // 2^-53 of its two products' magnitudes. A component beyond 2^-49 of them is nonzero.
    double a[3], b[3];
    for (int k = 0; k < 3; ++k) {
        a[k] = double(p[1][k]) - double(p[0][k]);
        b[k] = double(p[2][k]) - double(p[0][k]);
    }
    for (int e = 0; e < 3; ++e) {
        const int i = (e + 1) % 3, j = (e + 2) % 3;
        const double x = a[i] * b[j], y = a[j] * b[i];
        if (std::abs(x - y) > 0x1p-49 * (std::abs(x) + std::abs(y))) return false;
    }
    // Within rounding of zero on every axis (rare: slivers): exact integers.
    return collinearInIntegers(p);
}

} // namespace nori
