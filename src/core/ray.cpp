/// \file ray.cpp
/// \brief Error bounds for rays spawned from surfaces: how far from its triangle a secondary ray
/// must start so that the intersectors cannot find that triangle again.
///
/// Notation: u = 2^-24 is the unit roundoff, gamma_n = n u / (1 - n u) (roundingBound), R the largest
/// coordinate difference |p_i - o|_inf between a corner of the triangle and the ray origin o, A the
/// triangle's area, h the distance of o from the triangle's plane. First-order terms in u only; the
/// constants below carry a factor of about two over what the derivation needs to cover the rest.
///
/// 1. Rounding of the hit point. p = b0 p0 + b1 p1 + b2 p2 with b0 = (1 - b1) - b2 computed in float.
///    The rounded barycentrics sum to 1 + e with |e| <= 2u (two roundings of numbers <= 1), so the exact
///    combination of the rounded barycentrics lies off the plane by at most |e| sum |b_i p_i|; the
///    three products and two sums add gamma_3 sum |b_i p_i| per component. Together: gamma_7
///    sum_i |b_i| |p_i| per component (interpolationError). The distance of p from the plane is then at
///    most sum_k |n_k| err_k. This bound scales with |p|: it is what fails far from the world origin.
///
/// 2. What the intersectors get wrong. Near the world origin the bound of 1 is tiny (a floor at y = 0
///    has none at all in y), yet a ray leaving the floor at a grazing angle was found to re-hit it:
///    both kernels compute t from vertex coordinates relative to the origin, whose errors scale with
///    R, not with |p|. For the watertight kernel (Woop et al. 2013) with shear (sx, sy, sz):
///    - sheared corners x_i = a_i,kx - sx a_i,kz (a_i = p_i - o, |sx| <= 1): |x_i| <= 2R and the
///      computed value is within 6uR of the exact shear of the exact ray (same for y_i);
///    - edge functions E_i = x_j y_k - y_j x_k: |E_i| <= 8R^2, error <= 64uR^2; det = sum E_i, error
///      <= 240uR^2;
///    - z_i = sz a_i,kz: |z_i| <= Z = R / |d_kz|, error <= 3u Z; T = sum E_i z_i, error <= 336uR^2 Z.
///    Exactly, E_i = det beta_i with beta_i the barycentrics of the point where the ray's line crosses
///    the plane, det = 2A (n.d) / d_kz and T = t* det with t* = -h / (n.d) < 0 for a ray leaving the
///    plane. The kernel reports a hit only if the computed E_i share a sign and t = T / det >= 0.
///    (a) If |det| > 240uR^2, the computed det has the exact sign; if also |T| = 2Ah / |d_kz| exceeds
///        336uR^2 Z, i.e. h > 168uR^3 / A, so does T, and the computed t is negative: no hit.
///    (b) Otherwise the ray is nearly parallel to the plane (|n.d| <= 120uR^2 |d_kz| / A). From
///        E_i d_kz = ((p_j - o) x (p_k - o)).d and o = c + h n (c the foot point, inside the triangle):
///        E_i d_kz = 2 A_i(c) (n.d) - h ((p_j - p_k) x n).d, with |A_i(c)| <= A. The three vectors
///        (p_j - p_k) x n sum to zero and one of their projections on d has magnitude at least
///        |d_par| w, w = 2A / l_max >= A / (sqrt(3) R) the triangle's smallest width, so for either
///        common sign some E_i has the other sign by at least (h |d| w / 2 - 240uR^2 |d_kz|) / |d_kz|.
///        That exceeds its error 64uR^2 when h > 608uR^2 / w, i.e. h > 1053uR^3 / A: no hit.
///    So h >= 2106u R^3 / (2A) suffices for every direction that leaves the plane. Möller-Trumbore
///    computes the same two triple products ((o - p0) x e1).e2 and (d x e2).e1 from |o - p0|, |e1|,
///    |e2| <= 2R with the same structure of errors, plus the rounding of its stored edges (a tilt of
///    the plane by u, i.e. a shift of at most 2uR at o): the same bound with the factor two covers it.
///    We use 2^12 u R^3 / (2A). A coplanar neighbour sharing an edge or corner is covered as long as
///    its own R^3 / A is not larger (R is measured from o, so a neighbour of similar size is).
///    Random tests (both kernels, 4.8M rays at grazing angles down to 1e-8 rad, triangles from 1e-3 to
///    1e3 wide near and far from the origin, with a coplanar neighbour) still re-hit with 1/64 of this
///    offset and never with 1/16 of it.
///
/// 3. Slivers. R^2 / (2A) grows without bound for needle-like triangles, and so would the offset;
///    it is capped at 16 (an offset of at most R / 256). Beyond that the bound is no longer proven; in
///    the random tests with slivers up to 1000:1 the capped offset kept a margin of 16. A per-triangle check inside the
///    kernels (reject t below the triangle's own error bound, as pbrt-v4 does) would remove the cap
///    and the neighbour condition; the kernels are not changed here.
///
/// 4. The far end of a shadow segment to a point q on another triangle: q is moved off its triangle by
///    the same offset, which covers the case where the segment is short. For a long segment (length D)
///    the kernels' relative error in t near q grows like u (D / R_q) / cos(theta_q); the segment stops
///    ShadowEpsilon = 2^-12 short of q. Measured worst case over a million random segments
///    (D / R_q up to 10^4, cos(theta_q) down to 0.01): 1 - t = 5.2e-6 (watertight), 1.3e-4 (MT); without
///    the offset of q it reaches 8.8e-4 and 2.1e-2.
#include <nori/ray.h>
#include <algorithm>

namespace nori {

Vector3f interpolationError(const Point3f &p0, const Point3f &p1, const Point3f &p2, float b0, float b1, float b2) {
    Vector3f sum = std::abs(b0) * p0.cwiseAbs() + std::abs(b1) * p1.cwiseAbs() + std::abs(b2) * p2.cwiseAbs();
    return roundingBound(7) * sum;
}

float spawnOffset(const Point3f &p0, const Point3f &p1, const Point3f &p2, const Point3f &p, const Vector3f &pError,
                  const Normal3f &ng) {
    return spawnOffset(p0, p1, p2, p, pError, ng, (p1 - p0).cross(p2 - p0).norm());
}

float spawnOffset(const Point3f &p0, const Point3f &p1, const Point3f &p2, const Point3f &p, const Vector3f &pError,
                  const Normal3f &ng, float twiceArea) {
    // Section 1: the distance of p from the plane.
    float interpolation = ng.cwiseAbs().dot(pError);
    // Section 2: R from p plus what separates p from the origin o (absorbed in the factor 2 margin).
    float R = std::max({(p0 - p).cwiseAbs().maxCoeff(), (p1 - p).cwiseAbs().maxCoeff(), (p2 - p).cwiseAbs().maxCoeff()}) +
              pError.maxCoeff();
    // Section 3: R^2 / (2A), capped for slivers (and degenerate triangles, which no kernel reports).
    const float maxShape = 16.0f;
    float shape = twiceArea > 0.0f ? std::min(R * R / twiceArea, maxShape) : maxShape;
    if (!std::isfinite(shape)) shape = maxShape;
    float kernel = 0x1p-12f * R * shape;  // 2^12 u R^3 / (2A)
    return (interpolation + kernel) * (1.0f + roundingBound(4));
}

} // namespace nori
