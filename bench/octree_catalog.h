/// \file octree_catalog.h
/// \brief The octree configurations to benchmark: the cross product of the option lists,
/// checked against what the registered "octree" accel accepts.
#pragma once

#include "bench_options.h"
#include "bench_results.h"
#include <memory>

namespace nori::bench {

class OctreeCatalog {
public:
    /// \brief Is an accel named "octree" registered in this build?
    static bool available();

    /// \brief Enumerate (and validate) the configurations of \p options. Throws
    /// std::invalid_argument (one line) when the octree rejects a value given on the command
    /// line; rejected default values are skipped (see skipped()). When the octree's own
    /// defaults are not in the cross product they are added as one more run.
    explicit OctreeCatalog(const BenchOptions &options);

    const std::vector<OctreeConfig> &configs() const { return m_configs; }
    /// \brief The octree's own defaults (as far as its toString() reveals them).
    const OctreeConfig &defaults() const { return m_defaults; }
    /// \brief The traversals used when --traversals is not given.
    const std::vector<std::string> &traversals() const { return m_traversals; }
    /// \brief Default list values the octree rejected (e.g. a depth beyond its limit), with
    /// the reason; values given on the command line are errors instead.
    const std::vector<std::string> &skipped() const { return m_skipped; }

    /// \brief A new, unbuilt octree with the settings of \p config.
    static std::unique_ptr<Accel> create(const OctreeConfig &config);

private:
    static OctreeConfig probeDefaults();
    static bool accepts(const OctreeConfig &config, std::string &error);

    OctreeConfig m_defaults;
    std::vector<std::string> m_traversals;
    std::vector<OctreeConfig> m_configs;
    std::vector<std::string> m_skipped;
};

} // namespace nori::bench
