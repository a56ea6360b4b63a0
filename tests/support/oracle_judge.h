/// \file oracle_judge.h
/// \brief Explains a disagreement between two closest-hit answers for one ray (an accelerator
/// under test and Embree robust): the rule of the oracle tests, shared with nori-bench.
///
/// Per ray (for any-hit queries, the closest hits behind the two answers are judged):
///  * match:  same hit/miss; when both hit, the same triangle and both hit points within eps
///            of it (t may differ by more for a grazing ray: rounding across the plane is
///            amplified by 1 / sin(angle), and for a hit much nearer than the origin's
///            magnitude, rounding of the origin dominates t).
///  * tie:    both hit different triangles and each hit point lies within eps of the other's
///            triangle (duplicated / back-to-back triangles, hits on a shared edge or vertex,
///            crossing triangles): both answers are the closest hit up to rounding.
///  * edge:   the answers differ and the ray passes within eps of the boundary of the nearer
///            of the two hit triangles (for a hit/miss pair: of the triangle that was hit), so
///            moving the ray by eps would flip that hit.
///  * range:  the answers differ and the nearer hit's t lies within eps of ray.mint or ray.maxt.
///  * oracle: the first answer (the accelerator's) is the exact one and the second (the oracle's)
///            is not, decided in double precision on the triangles the two answers name: e.g. a
///            hit on a huge triangle that Embree's float barycentrics put 1.4e-4 across the
///            diagonal of a 2000-unit quad (only the first answer can be excused this way).
///  * anything else is unexplained.
/// eps = 2^-17 (about 64 float ulps) of the problem's scale: the largest coordinate magnitude
/// of the ray origin, the hit points and t |d|. All geometry is evaluated in double.
#pragma once

#include <nori/accel.h>
#include <vector>

namespace nori {

/// \brief The verdicts, in the order of their counters.
enum Verdict { Match, Tie, Edge, Range, OracleError, Unexplained, VerdictCount };
/// \brief "match", "tie", "edge", "range", "oracle", "UNEXPLAINED".
const char *verdictName(int verdict);

/// \brief Applies the rule of the file comment over one global triangle numbering.
class OracleJudge {
public:
    /// \brief The scale at which the edge rule judges a ray that passes near an edge.
    enum class EdgeScale {
        Problem,  ///< eps of the file comment: the ray's and the hits' coordinates
        /// eps or 2^-17 of the nearer triangle's corners' distance from the ray origin, whichever
        /// is larger: how finely a float kernel that works on the corners relative to the origin
        /// (Möller–Trumbore's o - p0, e1, e2) can place an edge. Near the diagonal of a ground
        /// quad 100,000 across, its rounding leaks rays through the shared edge far beyond the
        /// problem's eps; an exact kernel is judged with Problem.
        KernelCorners,
    };
    explicit OracleJudge(const std::vector<const Mesh *> &meshes, EdgeScale edgeScale = EdgeScale::Problem);

    /// \brief Verdict for \p ray answered by (hitA, a), the accelerator under test, and (hitB, b),
    /// the oracle; symmetric in the two answers except for OracleError.
    Verdict judge(const Ray3f &ray, bool hitA, const Hit &a, bool hitB, const Hit &b) const;
    /// \brief Referee for answers that differ: is (\p hit, \p h) the exact closest hit among
    /// the triangles \p candidates (the ones the compared answers name), decided in double?
    /// A hit is right when its triangle passes within eps of its point, that point lies on a
    /// crossing of some candidate (within eps in t: a hit on either of two triangles sharing an
    /// edge is the same answer) and no crossing lies nearer by more than eps; a miss is right
    /// when no candidate is crossed. Returns +1 right, -1 wrong, 0
    /// undecidable (a crossing within ~1e-9 of the problem's scale of an edge or of the
    /// segment's ends). The exact arithmetic that decides which of two disagreeing float
    /// answers, e.g. on rays past a thin blade's edge, is the true one.
    int referee(const Ray3f &ray, bool hit, const Hit &h, const std::vector<uint32_t> &candidates) const;
    /// \brief eps of the rule for these answers (exposed for tests and reports).
    double epsilon(const Ray3f &ray, bool hitA, const Hit &a, bool hitB, const Hit &b) const;

private:
    Eigen::Vector3d corner(uint32_t prim, int k) const;
    bool rayPassesEdge(const Ray3f &ray, const Hit &h, double eps) const;
    /// Exact (double) intersection of the ray's segment with triangle \p prim: t on its plane and
    /// the smallest signed distance of that point from the triangle's edges (negative: outside).
    bool exactOnPlane(const Ray3f &ray, uint32_t prim, double &t, double &inside) const;
    bool oracleIsWrong(const Ray3f &ray, bool hitA, const Hit &a, bool hitB, const Hit &b, double eps) const;

    std::vector<const Mesh *> m_meshes;
    std::vector<uint32_t> m_offsets{0};
    EdgeScale m_edgeScale;
};

} // namespace nori
