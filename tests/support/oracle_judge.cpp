/// \file oracle_judge.cpp
/// \brief OracleJudge: the tie / edge / range rule in double precision.
#include "oracle_judge.h"
#include "test_geometry.h"
#include <algorithm>

namespace nori {

namespace {
V3d point(const Ray3f &ray, const Hit &h) { return ray.o.cast<double>() + double(h.t) * ray.d.cast<double>(); }
} // namespace

const char *verdictName(int verdict) {
    static const char *names[] = {"match", "tie", "edge", "range", "oracle", "UNEXPLAINED"};
    return verdict >= 0 && verdict < VerdictCount ? names[verdict] : "?";
}

OracleJudge::OracleJudge(const std::vector<const Mesh *> &meshes, EdgeScale edgeScale)
    : m_meshes(meshes), m_edgeScale(edgeScale) {
    for (const Mesh *m : meshes) m_offsets.push_back(m_offsets.back() + m->triangleCount());
}

V3d OracleJudge::corner(uint32_t prim, int k) const {
    size_t idx = size_t(std::upper_bound(m_offsets.begin(), m_offsets.end(), prim) - m_offsets.begin()) - 1;
    return m_meshes[idx]->vertex(prim - m_offsets[idx], k).cast<double>();
}

double OracleJudge::epsilon(const Ray3f &ray, bool hitA, const Hit &a, bool hitB, const Hit &b) const {
    double s = ray.o.cast<double>().cwiseAbs().maxCoeff();
    for (const Hit *h : {hitA ? &a : nullptr, hitB ? &b : nullptr}) {
        if (!h) continue;
        s = std::max(s, point(ray, *h).cwiseAbs().maxCoeff());
        s = std::max(s, double(h->t) * ray.d.cast<double>().norm());
    }
    return 0x1p-17 * s;
}

Verdict OracleJudge::judge(const Ray3f &ray, bool hitA, const Hit &a, bool hitB, const Hit &b) const {
    if (!hitA && !hitB) return Match;
    double eps = epsilon(ray, hitA, a, hitB, b);
    double dnorm = ray.d.cast<double>().norm();
    if (hitA && hitB) {
        if (pointTriangleDistance(point(ray, a), corner(b.prim, 0), corner(b.prim, 1), corner(b.prim, 2)) <= eps &&
            pointTriangleDistance(point(ray, b), corner(a.prim, 0), corner(a.prim, 1), corner(a.prim, 2)) <= eps)
            return a.prim == b.prim ? Match : Tie;
    }
    // The nearer hit decides: it is the one the other side missed.
    const Hit &nearer = !hitB || (hitA && a.t < b.t) ? a : b;
    if (std::abs(double(nearer.t) - double(ray.maxt)) * dnorm <= eps ||
        std::abs(double(nearer.t) - double(ray.mint)) * dnorm <= eps)
        return Range;
    if (rayPassesEdge(ray, nearer, eps)) return Edge;
    if (oracleIsWrong(ray, hitA, a, hitB, b, eps)) return OracleError;
    return Unexplained;
}

bool OracleJudge::exactOnPlane(const Ray3f &ray, uint32_t prim, double &t, double &inside) const {
    V3d o = ray.o.cast<double>(), d = ray.d.cast<double>();
    V3d p[3] = {corner(prim, 0), corner(prim, 1), corner(prim, 2)};
    V3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    double nd = n.dot(d);
    if (nd == 0.0 || n.squaredNorm() == 0.0) return false;
    t = n.dot(p[0] - o) / nd;
    V3d x = o + t * d, unit = n.normalized();
    inside = Infinity;
    for (int k = 0; k < 3; ++k) {
        V3d edge = p[(k + 1) % 3] - p[k];
        // Signed distance of x from the edge's line, positive towards the triangle's interior.
        inside = std::min(inside, edge.cross(x - p[k]).dot(unit) / edge.norm());
    }
    return true;
}

/// The accelerator's answer a is exact and the oracle's b is not, with a margin far above the
/// rounding of the double computation: a's triangle is crossed inside (or a misses), at a's t
/// within eps, and b's triangle is exactly missed, or crossed farther than a's hit.
bool OracleJudge::oracleIsWrong(const Ray3f &ray, bool hitA, const Hit &a, bool hitB, const Hit &b, double eps) const {
    const double margin = 1e-9 * eps * 0x1p17;  // ~1e-9 of the problem's scale
    double dn = ray.d.cast<double>().norm();
    double tA = Infinity;
    if (hitA) {
        double inside;
        if (!exactOnPlane(ray, a.prim, tA, inside) || inside < margin) return false;
        if (std::abs(tA - double(a.t)) * dn > eps || tA < double(ray.mint) || tA > double(ray.maxt)) return false;
    }
    if (!hitB) return hitA;  // the oracle missed a triangle the ray crosses inside
    double tB, insideB;
    if (!exactOnPlane(ray, b.prim, tB, insideB)) return true;  // parallel: the oracle cannot hit it
    bool bMissed = insideB < -margin || tB < double(ray.mint) - margin / dn || tB > double(ray.maxt) + margin / dn;
    return bMissed || (hitA && tB > tA + margin / dn);
}

int OracleJudge::referee(const Ray3f &ray, bool hit, const Hit &h, const std::vector<uint32_t> &candidates) const {
    const double dn = ray.d.cast<double>().norm();
    const double eps = epsilon(ray, hit, h, false, h);  // the judge's eps: same point up to float rounding
    const double margin = 1e-9 * std::max(eps * 0x1p17, 1e-30);
    const double lo = double(ray.mint), hi = double(ray.maxt), m = margin / dn;
    // The exact crossings of the candidates: certain (inside and within [mint, maxt] by more
    // than the margin) or possible (within the margin of that).
    double best = Infinity, bestDoubt = Infinity;  // nearest certain crossing, nearest possible one
    bool onCertain = false, onPossible = false;    // the answer's point lies on such a crossing
    for (uint32_t prim : candidates) {
        double t, inside;
        if (!exactOnPlane(ray, prim, t, inside)) continue;
        const bool certain = inside > margin && t > lo + m && t < hi - m;
        const bool possible = inside >= -margin && t >= lo - m && t <= hi + m;
        if (certain) best = std::min(best, t);
        if (possible) bestDoubt = std::min(bestDoubt, t);
        // Same point: a hit on either of two triangles sharing an edge (or overlapping) at the
        // same t is the same answer, whichever triangle it names.
        if (hit && std::abs(t - double(h.t)) * dn <= eps) {
            onCertain |= certain;
            onPossible |= possible;
        }
    }
    if (!hit) {
        if (best < Infinity) return -1;  // a candidate is certainly crossed
        return bestDoubt < Infinity ? 0 : 1;
    }
    // The named triangle itself must pass within eps of the claimed point (as for a tie).
    double tNamed, insideNamed;
    if (!exactOnPlane(ray, h.prim, tNamed, insideNamed) || insideNamed < -eps ||
        std::abs(tNamed - double(h.t)) * dn > eps)
        return -1;
    if (!onPossible) return -1;                             // no candidate is crossed where it claims
    if ((double(h.t) - best) * dn > eps) return -1;         // a certain crossing lies nearer
    if (!onCertain || (double(h.t) - bestDoubt) * dn > eps) return 0;
    return 1;
}

/// Does the ray pass within eps of one of the triangle's three edges, i.e. would moving it by
/// eps turn this hit into a miss? Only the piece of the ray that can come near the triangle
/// (two edge lengths around the hit) is considered.
bool OracleJudge::rayPassesEdge(const Ray3f &ray, const Hit &h, double eps) const {
    V3d o = ray.o.cast<double>(), d = ray.d.cast<double>();
    V3d a = corner(h.prim, 0), b = corner(h.prim, 1), c = corner(h.prim, 2);
    if (m_edgeScale == EdgeScale::KernelCorners)
        eps = std::max({eps, 0x1p-17 * (a - o).cwiseAbs().maxCoeff(), 0x1p-17 * (b - o).cwiseAbs().maxCoeff(),
                        0x1p-17 * (c - o).cwiseAbs().maxCoeff()});
    double size = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    double span = 2.0 * size / d.norm();
    double t0 = std::max(double(ray.mint), double(h.t) - span), t1 = std::min(double(ray.maxt), double(h.t) + span);
    V3d r0 = o + t0 * d, r1 = o + t1 * d;
    return segmentDistance(r0, r1, a, b) <= eps || segmentDistance(r0, r1, b, c) <= eps ||
           segmentDistance(r0, r1, c, a) <= eps;
}

} // namespace nori
