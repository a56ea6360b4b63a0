/// \file bench_results.h
/// \brief What nori-bench measured, as plain data for the JSON and Markdown writers.
#pragma once

#include "accuracy.h"
#include <nori/accel.h>
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace nori::bench {

/// \brief Timing and accuracy of one contender on one ray set.
struct SetTiming {
    std::string name;         ///< primary, diffuse or shadow
    size_t rays = 0;
    double ms = 0.0;          ///< median over the repeats
    double mraysPerS = 0.0;
    double embreeMs = 0.0;    ///< median of the Embree runs interleaved with this contender
    double ratioVsEmbree = 0.0;  ///< embreeMs / ms
    bool hasAccuracy = false;
    Accuracy accuracy;        ///< against Embree robust
    std::vector<double> samples;  ///< every timed run, in order
};

/// \brief One octree configuration (the properties nori-bench sets).
struct OctreeConfig {
    std::string buildRule;    ///< empty: the octree's own default rule
    int maxDepth = 0;
    int leafSize = 0;
    std::string overlap, traversal, intersector;
    bool isDefault = false;   ///< equals the octree's own defaults
    bool useDefaults = false; ///< create with an empty property list (--default-only)
    /// --octree-set: further properties, on top of the settings above (not part of sameSettings:
    /// the defaults with these are still the run the renderer's defaults are compared in).
    std::vector<std::pair<std::string, std::string>> properties;

    std::string label() const;
    bool sameSettings(const OctreeConfig &o) const {
        return buildRule == o.buildRule && maxDepth == o.maxDepth && leafSize == o.leafSize &&
               overlap == o.overlap && traversal == o.traversal && intersector == o.intersector;
    }
};

/// \brief One contender: its build and its three ray sets.
struct RunResult {
    std::string accel;        ///< "octree", "brute"
    bool hasConfig = false;   ///< config is meaningful (octree)
    OctreeConfig config;
    double buildMs = 0.0;
    std::vector<AccelStat> stats;  ///< the accel's statistics() (build_ms, nodes, bytes, ...)
    std::array<SetTiming, 3> sets;

    /// \brief A statistic by name, or \p fallback.
    double stat(const std::string &name, double fallback = -1.0) const {
        for (const AccelStat &s : stats)
            if (s.name == name) return s.value;
        return fallback;
    }
    bool hasStat(const std::string &name) const { return stat(name, -12345.0) != -12345.0; }
};

/// \brief Embree (fast or robust) on one mesh.
struct EmbreeResult {
    double buildMs = 0.0;
    long long bytes = 0;
    std::array<SetTiming, 3> sets;
};

/// \brief Everything measured on one input.
struct MeshResult {
    std::string mesh;
    uint64_t triangles = 0;
    int threads = 1;
    double loadMs = 0.0;
    int width = 0, height = 0, spp = 0, repeats = 0;
    std::string clock = "wall";  ///< what timed the ray sets: "wall" or "cpu" (--cpu-time)
    /// The machine, without which ratios from two machines cannot be compared: the CPU's
    /// name, whether it has AVX-512 (Embree picks its kernels by the CPU at run time), and the
    /// lanes of the octree's kernels (fixed at compile time by NORI_ARCH: 16, 8 or 1).
    std::string cpu;
    bool cpuAvx512 = false;
    int octreeLanes = 1;
    std::string camera;       ///< "framing" (automatic, fov 30) or "scene"
    double rayGenerationMs = 0.0;
    EmbreeResult embree;      ///< default (non-robust) flags: the speed peer
    EmbreeResult embreeRobust;  ///< RTC_SCENE_FLAG_ROBUST: the accuracy reference
    std::vector<RunResult> runs;
    std::vector<std::string> notes;  ///< e.g. default list values the octree rejected
};

} // namespace nori::bench
