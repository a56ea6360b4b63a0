/// \file bench_options.h
/// \brief Command line of nori-bench: what to load, which contenders to run, where to write.
#pragma once

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace nori {
class CliApp;
}

namespace nori::bench {

/// \brief Every setting of one nori-bench invocation, after parsing and defaulting.
struct BenchOptions {
    std::vector<std::string> meshes;  ///< --mesh (repeatable)
    std::string scene;                ///< --scene
    int width = 512, height = 512, spp = 4;
    std::vector<std::string> buildRules;   ///< empty: the octree's default rule
    std::vector<int> depths{20, 25, 30};
    std::vector<int> leafSizes{10};
    std::vector<std::string> overlaps{"exact", "bbox"};
    std::vector<std::string> traversals;   ///< empty: every traversal the octree offers
    std::vector<std::string> intersectors{"mt", "watertight"};
    /// --octree-set NAME=VALUE (repeatable): further octree properties for every octree run
    /// (e.g. termination=false, fold=false), in the order given.
    std::vector<std::pair<std::string, std::string>> octreeProperties;
    int threads = 0;                  ///< 0: all hardware threads
    int repeats = 3;
    /// --cpu-time: time ray sets by the thread's CPU time instead of the wall clock (single
    /// thread only): on a shared machine, time spent descheduled is not counted for either side.
    bool cpuTime = false;
    bool defaultOnly = false;
    bool quick = false;
    bool noBrute = false;             ///< --no-brute (extra)
    size_t bruteRays = 4096;          ///< --brute-rays: rays per set for brute force (extra)
    size_t bruteMaxTriangles = 100000;
    bool render = false;              ///< --render: full renders with the octree and with Embree
    std::string renderImages;         ///< --render-images DIR: both renders and their difference
    bool embreeRobust = false;        ///< --embree-robust: render mode's Embree in robust mode
    std::string jsonPath, markdownPath, plotsDir;
    /// --dump-disputed FILE: every refereed ray of the octree runs, with the three answers, their
    /// verdicts and the named triangles (hex floats), for replaying hard rays in tests.
    std::string dumpDisputed;
    /// --dump-answers FILE: every ray and the octree runs' answer to it (binary, see bench/README.md),
    /// to compare two builds' answers ray by ray.
    std::string dumpAnswers;
    std::string python = "/usr/bin/python3";
    std::vector<std::string> searchPath;  ///< -a (repeatable)
    std::set<std::string> given;      ///< the options that appeared on the command line

    bool wasGiven(const std::string &option) const { return given.count(option) != 0; }

    /// \brief Rays per set, as configured.
    size_t cameraRayCount() const { return size_t(width) * size_t(height) * size_t(spp); }
};

/// \brief Declares BenchOptions on a CliApp and completes them after parsing.
class OptionParser {
public:
    /// \brief Declare every option of nori-bench on \p cli, filling \p options while it parses.
    static void declare(CliApp &cli, BenchOptions &options);
    /// \brief After a successful parse: record what was given, apply --quick and -a, and check
    /// what CLI11 cannot. Throws UsageError.
    static void finish(CliApp &cli, BenchOptions &options);
};

} // namespace nori::bench
