/// \file bench_runner.h
/// \brief Runs every contender on one input, interleaved with Embree, and collects the results.
#pragma once

#include "bench_options.h"
#include "bench_results.h"
#include "mesh_source.h"
#include "octree_catalog.h"
#include "ray_timer.h"
#include <cstdio>
#include <memory>

namespace nori {
class EmbreeOracle;
class OracleJudge;
}

namespace nori::bench {

class RayWorkload;
struct RaySet;
struct Accuracy;

class BenchRunner {
public:
    BenchRunner(const BenchOptions &options, const OctreeCatalog &catalog);

    /// \brief Measure everything on \p input (progress on stderr).
    MeshResult run(const BenchInput &input) const;

private:
    /// \brief Time \p tracer on every set of \p work, each run followed by one of \p embree;
    /// fills timings and accuracy. \p embreeSamples collects the Embree runs per set.
    template <typename Tracer>
    std::array<SetTiming, 3> interleaved(const Tracer &tracer, const EmbreeOracle &embree, const RayWorkload &work,
                                         std::array<std::vector<double>, 3> *embreeSamples) const;
    RunResult runAccel(const std::string &accelName, Accel &accel, const OctreeConfig *config,
                       const BenchInput &input, const EmbreeOracle &embree, const RayWorkload &work,
                       std::array<std::vector<double>, 3> *embreeSamples) const;
    void progress(const std::string &what, const RunResult &run) const;
    /// \brief Decide each mismatch of \p accuracy (on \p set, answered by \p tracer) in exact
    /// arithmetic against the reference (m_robust), untimed.
    /// \p peer (Embree default, whose \p peerAnswers were traced beside the contender's) is
    /// refereed on the same rays.
    template <typename Tracer>
    void referee(const Tracer &tracer, const EmbreeOracle &peer, const RaySet &set, const std::vector<float> &peerAnswers,
                 Accuracy &accuracy) const;

    /// \brief --dump-disputed: one refereed ray, its three answers and verdicts, the triangles.
    void dumpRay(const RaySet &set, uint32_t index, const bool hit[3], const Hit hits[3], const int verdict[3]) const;

    // The referee's context, set by run() for the input being measured.
    mutable const OracleJudge *m_judge = nullptr;
    mutable const EmbreeOracle *m_robust = nullptr;
    // --dump-disputed: the file, the octree run being refereed ("" for Embree's own runs) and
    // the input's meshes (global triangle ids in their order).
    std::shared_ptr<std::FILE> m_dump, m_answers;
    mutable std::string m_dumpWho;
    mutable std::vector<const Mesh *> m_dumpMeshes;

    const BenchOptions &m_options;
    const OctreeCatalog &m_catalog;
    RayTimer m_timer;
    int m_threads;
};

} // namespace nori::bench
