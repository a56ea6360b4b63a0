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

namespace {
/// The edge volumes that the double evaluation left unsettled, in exact integers (out of line:
/// inlined, the integers' large stack frame was set up on every call, and the double evaluation
/// around it spilled its values through general registers: 298 instructions per call, most of
/// them for rays the double evaluation settles).
[[gnu::noinline]] void volumesInIntegers(const float o[3], const float d[3], const float p[3][3], const bool open[3],
                                         double vol[3]) {
    Int ds[3], qs[3][3];
    for (int k = 0; k < 3; ++k) {
        ds[k] = scaled(d[k]);
        const Int ok = scaled(o[k]);
        for (int c = 0; c < 3; ++c) qs[c][k] = scaled(p[c][k]) - ok;
    }
    for (int e = 0; e < 3; ++e) {
        if (!open[e]) continue;
        const Int v = volume(ds, qs[(e + 1) % 3], qs[(e + 2) % 3]);
        // Rounded to double (a nonzero volume is at least 2^-447 of it: no underflow).
        vol[e] = v.is_zero() ? 0.0 : std::ldexp(v.convert_to<double>(), -447);
    }
}
} // namespace

namespace {
/// Four doubles, one per edge (the fourth unused): the three edge volumes are evaluated side by
/// side, with the same operations in the same order as one edge alone (no contraction: see
/// CMakeLists.txt), so the bits do not depend on the vector width the compiler picks. GCC and
/// clang vector extensions: AVX where the build targets it, pairs of SSE2 operations otherwise.
typedef double Edge4 __attribute__((vector_size(32)));
typedef uint64_t Bits4 __attribute__((vector_size(32)));
// (No helper functions taking or returning these: without AVX their ABI differs, which GCC and
// clang warn about. |x| is written out as clearing the sign bits, one operation.)
#define NORI_ABS4(x) (Edge4(Bits4(x) & kMagnitude))
} // namespace

bool exactEdgeVolumes(const float o[3], const float d[3], const float p[3][3], double vol[3]) {
    // Corners relative to the origin in double, one vector per axis (corner c in element c, and
    // corner 0 again in the unused fourth: a copy costs less than a zero): each difference of
    // floats is exact unless their exponents lie more than 29 apart, and then off by at most a
    // relative 2^-53.
    Edge4 q[3];
    for (int k = 0; k < 3; ++k) {
        const double ok = o[k], q0 = double(p[0][k]) - ok;
        q[k] = Edge4{q0, double(p[1][k]) - ok, double(p[2][k]) - ok, q0};
    }
    // Edge e (volume vol[e], the weight of corner e) spans corners b = e + 1 and c = e + 2.
    Edge4 b[3], c[3];
    for (int k = 0; k < 3; ++k) {
        b[k] = __builtin_shufflevector(q[k], q[k], 1, 2, 0, 3);
        c[k] = __builtin_shufflevector(q[k], q[k], 2, 0, 1, 3);
    }
    // (b x c) per edge, from its six products.
    const Edge4 yz = b[1] * c[2], zy = b[2] * c[1], zx = b[2] * c[0], xz = b[0] * c[2], xy = b[0] * c[1], yx = b[1] * c[0];
    const Edge4 x = yz - zy, y = zx - xz, z = xy - yx;
    const double dx = d[0], dy = d[1], dz = d[2];
    const Edge4 v = dx * x + dy * y + dz * z;
    // First-order rounding error: 2 for the differences, 1 for each product, 1 for the cross
    // product's difference, 1 for the product with d and 2 for the sum: at most 7 units of 2^-53
    // of the sum of the terms' magnitudes (which cannot underflow or overflow: floats lie within
    // 2^-149 .. 2^128, products of three within double's range). 2^-49 = 16 units leaves room for
    // the rounding of the bound itself.
    const Bits4 kMagnitude = ~Bits4{} >> 1;
    const Edge4 terms = std::abs(dx) * (NORI_ABS4(yz) + NORI_ABS4(zy)) + std::abs(dy) * (NORI_ABS4(zx) + NORI_ABS4(xz)) +
                        std::abs(dz) * (NORI_ABS4(xy) + NORI_ABS4(yx));
    // A non-finite input makes some term infinite or NaN (a product with an infinity is one, and
    // so is 0 x inf), while finite inputs cannot overflow: one check after the arithmetic.
    if (!std::isfinite(terms[0] + terms[1] + terms[2])) return false;
    // Settled: beyond the bound, or all terms zero: each has a factor that is exactly zero (a
    // difference of floats is zero only when they are equal, and no product of nonzero ones
    // underflows), so the volume is exactly zero (a ray from a corner, as a shadow ray from a
    // vertex is).
    const auto settled = (NORI_ABS4(v) > 0x1p-49 * terms) | (terms == 0.0);
    bool open[3];
    for (int e = 0; e < 3; ++e) {
        vol[e] = v[e];
        open[e] = !settled[e];
    }
    if (!(open[0] || open[1] || open[2])) return true;
    // Within rounding of an edge line (or the ray in the plane): exact integers.
    volumesInIntegers(o, d, p, open, vol);
    return true;
}
#undef NORI_ABS4

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
