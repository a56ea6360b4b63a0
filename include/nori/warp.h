/// \file warp.h
/// \brief Warping functions: maps of uniform samples in [0,1)^2 to other domains, each with
/// the density (pdf) of the points it produces.
///
/// Every pair is checked by `nori-warptest NAME` (a chi^2 test of a histogram of warped points
/// against the integral of the pdf over each histogram cell).
#pragma once

#include <nori/common.h>

namespace nori {

/// \brief Identity on the unit square; density 1 on [0,1]^2.
Point2f squareToUniformSquare(const Point2f &sample);
float squareToUniformSquarePdf(const Point2f &p);

/// \brief Separable tent on [-1,1]^2: density (1 - |x|)(1 - |y|), by the inverse CDF per axis.
Point2f squareToTent(const Point2f &sample);
float squareToTentPdf(const Point2f &p);

/// \brief Uniform on the unit disk (radius sqrt(u), angle 2 pi v); density 1/pi inside.
Point2f squareToUniformDisk(const Point2f &sample);
float squareToUniformDiskPdf(const Point2f &p);

/// \brief Uniform on the triangle (0,0), (1,0), (0,1); density 2 inside. The result (b1, b2) is
/// the pair of barycentric coordinates of vertices 1 and 2 (b0 = 1 - b1 - b2), so a point on a
/// triangle p0 p1 p2 is b0 p0 + b1 p1 + b2 p2, uniform by area.
Point2f squareToUniformTriangle(const Point2f &sample);
float squareToUniformTrianglePdf(const Point2f &p);

/// \brief Uniform direction on the unit sphere; density 1/(4 pi).
Vector3f squareToUniformSphere(const Point2f &sample);
float squareToUniformSpherePdf(const Vector3f &v);

/// \brief Uniform direction on the hemisphere about +z; density 1/(2 pi) for z >= 0.
Vector3f squareToUniformHemisphere(const Point2f &sample);
float squareToUniformHemispherePdf(const Vector3f &v);

/// \brief Cosine-weighted direction about +z (Malley's method: a uniform disk sample lifted to
/// the hemisphere); density cos(theta)/pi for z > 0.
Vector3f squareToCosineHemisphere(const Point2f &sample);
float squareToCosineHemispherePdf(const Vector3f &v);

/// \brief Microfacet normal from the Beckmann distribution of roughness \p alpha, with density
/// D(m) cos(theta_m) = exp(-tan^2(theta)/alpha^2) / (pi alpha^2 cos^3(theta)) per steradian for
/// z > 0 (the normal distribution weighted by its projected area, which integrates to 1).
Vector3f squareToBeckmann(const Point2f &sample, float alpha);
float squareToBeckmannPdf(const Vector3f &m, float alpha);

} // namespace nori
