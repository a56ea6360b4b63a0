/// \file accuracy.h
/// \brief Compares a contender's answers with the Embree-robust reference.
#pragma once

#include <nori/ray.h>
#include <cstdint>
#include <vector>

namespace nori::bench {

/// \brief Disagreements of one ray set with the reference.
///
/// Two hits disagree when their hit points are further apart than both Tolerance times the
/// reference's distance and ScaleTolerance times the problem's scale (the largest coordinate
/// magnitude of the ray origin and the reference hit point). The second bound is what float
/// arithmetic can resolve at all: for a hit much nearer than the origin is far from the world
/// origin (a bounce from one wall into the adjacent one), every kernel's t carries an error of
/// a few ulps of the coordinates, which can be far more than 1e-4 of t itself. It is the eps of
/// the oracle tests' judge (tests/support/oracle_judge.h).
struct Accuracy {
    static constexpr double Tolerance = 1e-4;         ///< of the reference hit distance
    static constexpr double ScaleTolerance = 0x1p-17;  ///< of the problem's coordinate scale

    uint64_t mismatches = 0;    ///< hit/miss (occluded) differs, or the hit points differ (see above)
    uint64_t hitMiss = 0;       ///< of which: hit/miss differs
    double maxRelTError = 0.0;  ///< largest |t - t_ref| / t_ref over rays both report as hits

    /// Exact referee (BenchRunner; OracleJudge::referee) of the disputed rays: those where the
    /// contender or Embree default (the speed peer, timed beside it) differs from the reference.
    /// On each, the closest hits of the three are decided in double on the triangles they name;
    /// an answer is wrong when it is not the exact one (undecidable: the ray within ~1e-9 of the
    /// scale of an edge or a segment end, counted as right). So the contender's and Embree
    /// default's errors are counted on the same rays, and so are the reference's own.
    bool refereed = false;
    uint64_t disputed = 0;        ///< rays refereed
    uint64_t exactWrong = 0;      ///< of which the contender's answer is not the exact one
    uint64_t peerWrong = 0;       ///< of which Embree default's answer is not
    uint64_t referenceWrong = 0;  ///< of which Embree robust's answer is not

    std::vector<uint32_t> mismatchRays;  ///< indices of the mismatching rays (not reported)

    /// \brief Compare \p answers with \p reference (same encoding as RaySet::reference) for
    /// \p rays (the ray set both were traced on).
    static Accuracy compare(const std::vector<float> &answers, const std::vector<float> &reference,
                            const std::vector<Ray3f> &rays);
};

} // namespace nori::bench
