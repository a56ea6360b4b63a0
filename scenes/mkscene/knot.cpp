/// \file knot.cpp
/// \brief A trefoil-knot tube with a rotation-minimising frame, spiral ridges and beads.
#include "knot.h"
#include <algorithm>

namespace mkscene {

namespace {

// A (p,q) torus knot whose plane is horizontal (y up).
constexpr int kP = 2, kQ = 3;   // trefoil
constexpr double kMajor = 1.0;  // torus radius
constexpr double kMinor = 0.5;  // winding radius around the torus core
constexpr double kTube = 0.30;  // tube radius before relief
// Strands come no closer than ~0.83 and the curve's radius of curvature stays
// above ~0.71 with these radii, so a tube of radius <= 0.35 cannot self-intersect.

V3 knotCurve(double t) {
    double w = kMajor + kMinor * std::cos(kQ * t);
    return {w * std::cos(kP * t), kMinor * std::sin(kQ * t), w * std::sin(kP * t)};
}
V3 knotTangent(double t) {
    double w = kMajor + kMinor * std::cos(kQ * t);
    double dw = -kQ * kMinor * std::sin(kQ * t);
    return normalize({dw * std::cos(kP * t) - kP * w * std::sin(kP * t), kQ * kMinor * std::cos(kQ * t),
                      dw * std::sin(kP * t) + kP * w * std::cos(kP * t)});
}

// Relief on the tube: kRidges raised ridges spiralling kTwist full turns around the
// tube over one loop, with a row of beads in each groove. kRidges * kTwist must be an
// integer so the pattern closes seamlessly where the loop meets itself.
constexpr int kRidges = 8, kTwist = 2, kBeads = 72;
double relief(double u, double theta) {
    double phase = kRidges * (theta - 2.0 * kPi * kTwist * u);
    double ridge = std::pow(0.5 + 0.5 * std::cos(phase), 3.0);
    double groove = std::pow(0.5 - 0.5 * std::cos(phase), 6.0);
    double bead = std::pow(0.5 + 0.5 * std::cos(2.0 * kPi * kBeads * u), 4.0);
    return 1.0 + 0.16 * ridge + 0.14 * groove * bead;
}

} // namespace

void buildKnot(MeshBuilder &m, int nu, int nv, double floorY, double gap) {
    std::vector<V3> c(nu), t(nu), n(nu);
    for (int i = 0; i < nu; ++i) {
        double s = 2.0 * kPi * i / nu;
        c[i] = knotCurve(s);
        t[i] = knotTangent(s);
    }
    // Rotation-minimising frame by double reflection (Wang et al. 2008), so the tube does
    // not twist (a Frenet frame would flip at inflections).
    n[0] = normalize(cross(t[0], V3{0, 1, 0}));
    auto transport = [&](int i, int j, V3 r) {
        V3 v1 = c[j] - c[i];
        double c1 = dot(v1, v1);
        V3 rl = r - (2.0 / c1 * dot(v1, r)) * v1;
        V3 tl = t[i] - (2.0 / c1 * dot(v1, t[i])) * v1;
        V3 v2 = t[j] - tl;
        double c2 = dot(v2, v2);
        return c2 > 0 ? rl - (2.0 / c2 * dot(v2, rl)) * v2 : rl;
    };
    for (int i = 0; i + 1 < nu; ++i) n[i + 1] = normalize(transport(i, i + 1, n[i]));
    // The frame comes back rotated by some holonomy angle; spread its correction
    // evenly along the loop so the last ring lines up with the first.
    V3 back = normalize(transport(nu - 1, 0, n[nu - 1]));
    double holonomy = std::atan2(dot(cross(n[0], back), t[0]), dot(n[0], back));

    const uint32_t base = uint32_t(m.pos.size());
    for (int i = 0; i < nu; ++i) {
        double u = double(i) / nu;
        double a = -holonomy * u;
        V3 b0 = cross(t[i], n[i]);
        V3 nn = std::cos(a) * n[i] + std::sin(a) * b0;
        V3 bb = cross(t[i], nn);
        for (int j = 0; j < nv; ++j) {
            double th = 2.0 * kPi * j / nv;
            V3 d = std::cos(th) * nn + std::sin(th) * bb;
            m.add(c[i] + (kTube * relief(u, th)) * d);
        }
    }
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            uint32_t i1 = (i + 1) % nu, j1 = (j + 1) % nv;
            // With d = cos*n + sin*(t x n), (next ring) x (next around) points inward,
            // so quad() gets the rings as its first direction to face outward.
            m.quad(base + i * nv + j, base + i1 * nv + j, base + i * nv + j1, base + i1 * nv + j1);
        }

    // Scale to a 1-unit footprint and rest just above the floor.
    double extent = 0, ymin = 1e30;
    for (size_t i = base; i < m.pos.size(); ++i) {
        extent = std::max({extent, std::fabs(m.pos[i].x), std::fabs(m.pos[i].z)});
        ymin = std::min(ymin, m.pos[i].y);
    }
    const double scale = 0.5 / extent;
    for (size_t i = base; i < m.pos.size(); ++i) {
        V3 &p = m.pos[i];
        p = {p.x * scale, (p.y - ymin) * scale + floorY + gap, p.z * scale};
    }
}

} // namespace mkscene
