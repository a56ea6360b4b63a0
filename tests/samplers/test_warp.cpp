/// \file test_warp.cpp
/// \brief Each warp's pdf is the density of its map: the map's Jacobian determinant times the
/// pdf at the image is 1 everywhere, points land in the domain, and the pdfs integrate to 1.
/// (nori-warptest adds the chi^2 test of the same pairs; see tests/validation.)
#include <gtest/gtest.h>
#include <nori/warp.h>
#include <functional>

using namespace nori;

namespace {

using Planar = std::function<Point2f(const Point2f &)>;
using Spherical = std::function<Vector3f(const Point2f &)>;

/// |det J| of a planar map at \p u by central differences.
double planarJacobian(const Planar &warp, const Point2f &u, float h = 1e-3f) {
    Vector2f du = (warp(u + Point2f(h, 0)) - warp(u - Point2f(h, 0))) / (2 * h);
    Vector2f dv = (warp(u + Point2f(0, h)) - warp(u - Point2f(0, h))) / (2 * h);
    return std::abs(double(du.x()) * dv.y() - double(du.y()) * dv.x());
}

/// Area of the image of a small square on the sphere per unit area of the square.
double sphericalJacobian(const Spherical &warp, const Point2f &u, float h = 1e-3f) {
    Vector3f du = (warp(u + Point2f(h, 0)) - warp(u - Point2f(h, 0))) / (2 * h);
    Vector3f dv = (warp(u + Point2f(0, h)) - warp(u - Point2f(0, h))) / (2 * h);
    return du.cast<double>().cross(dv.cast<double>()).norm();
}

/// Interior sample points (away from the edges, where the central differences would step out).
std::vector<Point2f> interiorPoints() {
    std::vector<Point2f> points;
    for (float x = 0.03f; x < 0.99f; x += 0.0731f)
        for (float y = 0.03f; y < 0.99f; y += 0.0657f) points.emplace_back(x, y);
    return points;
}

/// Integral over the unit sphere of f, midpoint rule in (z, phi) (exact measure dz dphi).
double integrateSphere(const std::function<double(const Vector3f &)> &f, int nz = 2000, int nphi = 64) {
    double sum = 0.0;
    for (int i = 0; i < nz; ++i) {
        double z = -1.0 + (i + 0.5) * 2.0 / nz;
        double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        for (int j = 0; j < nphi; ++j) {
            double phi = (j + 0.5) * 2.0 * M_PI / nphi;
            sum += f(Vector3f(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)));
        }
    }
    return sum * (2.0 / nz) * (2.0 * M_PI / nphi);
}

} // namespace

TEST(Warp, PlanarPdfsAreTheDensitiesOfTheirMaps) {
    struct Case {
        const char *name;
        Planar warp;
        std::function<float(const Point2f &)> pdf;
    };
    std::vector<Case> cases = {
        {"square", squareToUniformSquare, squareToUniformSquarePdf},
        {"tent", squareToTent, squareToTentPdf},
        {"disk", squareToUniformDisk, squareToUniformDiskPdf},
        {"triangle", squareToUniformTriangle, squareToUniformTrianglePdf},
    };
    for (const Case &c : cases)
        for (const Point2f &u : interiorPoints()) {
            if (c.name == std::string("tent") && (std::abs(u.x() - 0.5f) < 2e-3f || std::abs(u.y() - 0.5f) < 2e-3f))
                continue;  // the tent's inverse CDF has a kink at 1/2
            double product = planarJacobian(c.warp, u) * c.pdf(c.warp(u));
            EXPECT_NEAR(product, 1.0, 2e-2) << c.name << " at " << u.transpose();
        }
}

TEST(Warp, SphericalPdfsAreTheDensitiesOfTheirMaps) {
    struct Case {
        const char *name;
        Spherical warp;
        std::function<float(const Vector3f &)> pdf;
    };
    std::vector<Case> cases = {
        {"uniform_sphere", squareToUniformSphere, squareToUniformSpherePdf},
        {"uniform_hemisphere", squareToUniformHemisphere, squareToUniformHemispherePdf},
        {"cosine_hemisphere", squareToCosineHemisphere, squareToCosineHemispherePdf},
    };
    for (float alpha : {0.05f, 0.3f, 1.0f})
        cases.push_back({"beckmann", [alpha](const Point2f &u) { return squareToBeckmann(u, alpha); },
                         [alpha](const Vector3f &m) { return squareToBeckmannPdf(m, alpha); }});
    for (const Case &c : cases)
        for (const Point2f &u : interiorPoints()) {
            Vector3f w = c.warp(u);
            EXPECT_NEAR(w.norm(), 1.0f, 1e-5f) << c.name;
            double product = sphericalJacobian(c.warp, u) * c.pdf(w);
            EXPECT_NEAR(product, 1.0, 2e-2) << c.name << " at " << u.transpose();
        }
}

TEST(Warp, PointsLandInTheDomain) {
    for (float x = 0.0f; x < 1.0f; x += 0.01f)
        for (float y = 0.0f; y < 1.0f; y += 0.01f) {
            Point2f u(x, y);
            EXPECT_LE(squareToTent(u).cwiseAbs().maxCoeff(), 1.0f);
            EXPECT_LE(squareToUniformDisk(u).norm(), 1.0f + 1e-6f);
            Point2f b = squareToUniformTriangle(u);
            EXPECT_GE(b.minCoeff(), 0.0f);
            EXPECT_LE(b.sum(), 1.0f + 1e-6f);
            EXPECT_GE(squareToUniformHemisphere(u).z(), 0.0f);
            EXPECT_GE(squareToCosineHemisphere(u).z(), 0.0f);
            EXPECT_GT(squareToBeckmann(u, 0.2f).z(), 0.0f);
        }
    // The largest sample below 1 stays finite for Beckmann (log of 1 - u).
    Vector3f m = squareToBeckmann(Point2f(0.5f, std::nextafter(1.0f, 0.0f)), 0.5f);
    EXPECT_TRUE(m.allFinite());
}

TEST(Warp, SphericalPdfsIntegrateToOne) {
    EXPECT_NEAR(integrateSphere([](const Vector3f &v) { return squareToUniformSpherePdf(v); }), 1.0, 1e-6);
    EXPECT_NEAR(integrateSphere([](const Vector3f &v) { return squareToUniformHemispherePdf(v); }), 1.0, 1e-3);
    EXPECT_NEAR(integrateSphere([](const Vector3f &v) { return squareToCosineHemispherePdf(v); }), 1.0, 1e-4);
    for (float alpha : {0.1f, 0.4f, 1.0f})
        EXPECT_NEAR(integrateSphere([alpha](const Vector3f &m) { return squareToBeckmannPdf(m, alpha); }, 200000, 4),
                    1.0, 2e-3)
            << alpha;
    // Outside their support the densities are zero.
    EXPECT_EQ(squareToUniformHemispherePdf(Vector3f(0, 0, -1)), 0.0f);
    EXPECT_EQ(squareToCosineHemispherePdf(Vector3f(1, 0, -1e-3f).normalized()), 0.0f);
    EXPECT_EQ(squareToBeckmannPdf(Vector3f(0, 0, -1), 0.3f), 0.0f);
    EXPECT_EQ(squareToUniformDiskPdf(Point2f(0.8f, 0.7f)), 0.0f);
    EXPECT_EQ(squareToTentPdf(Point2f(1.2f, 0.0f)), 0.0f);
    EXPECT_EQ(squareToUniformTrianglePdf(Point2f(0.6f, 0.6f)), 0.0f);
}

TEST(Warp, TriangleBarycentricsAreUniformByArea) {
    // Mean of a uniform point on the triangle is its centroid (1/3, 1/3).
    double sx = 0, sy = 0;
    const int n = 400;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            Point2f b = squareToUniformTriangle(Point2f((i + 0.5f) / n, (j + 0.5f) / n));
            sx += b.x();
            sy += b.y();
        }
    EXPECT_NEAR(sx / (n * n), 1.0 / 3.0, 1e-4);
    EXPECT_NEAR(sy / (n * n), 1.0 / 3.0, 1e-4);
}
