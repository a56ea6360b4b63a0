/// \file bench_options.h
/// \brief Command line of nori-bench: what to load, which contenders to run, where to write.
#pragma once

#include <set>
#include <string>
#include <vector>

namespace nori::bench {

/// \brief Every setting of one nori-bench invocation, after parsing and defaulting.
struct BenchOptions {
    std::vector<std::string> meshes;  ///< --mesh (repeatable)
    std::string scene;                ///< --scene
    int width = 512, height = 512, spp = 4;
    std::vector<int> depths{20, 25, 30};
    std::vector<int> leafSizes{10};
    std::vector<std::string> overlaps{"exact", "bbox"};
    std::vector<std::string> traversals;   ///< empty: every traversal the octree offers
    std::vector<std::string> intersectors{"mt", "watertight"};
    int threads = 0;                  ///< 0: all hardware threads
    int repeats = 3;
    bool defaultOnly = false;
    bool quick = false;
    bool noBrute = false;             ///< --no-brute (extra)
    size_t bruteRays = 4096;          ///< --brute-rays: rays per set for brute force (extra)
    size_t bruteMaxTriangles = 100000;
    bool render = false;              ///< --render: full renders with the octree and with Embree
    std::string renderImages;         ///< --render-images DIR: both renders and their difference
    bool embreeRobust = false;        ///< --embree-robust: render mode's Embree in robust mode
    std::string jsonPath, markdownPath, plotsDir;
    std::string python = "/usr/bin/python3";
    bool help = false;
    std::set<std::string> given;      ///< the options that appeared on the command line

    bool wasGiven(const std::string &option) const { return given.count(option) != 0; }

    /// \brief Rays per set, as configured.
    size_t cameraRayCount() const { return size_t(width) * size_t(height) * size_t(spp); }
};

/// \brief Parses argv into BenchOptions; throws std::invalid_argument with a one-line message.
class OptionParser {
public:
    /// \brief Parse \p argc / \p argv (argv[0] is skipped). Applies --quick and -a.
    static BenchOptions parse(int argc, char **argv);
    /// \brief The --help text.
    static std::string usage();
};

} // namespace nori::bench
