/// \file render_compare.h
/// \brief nori-bench's full-render mode: one scene rendered with the octree and with Embree.
#pragma once

#include "image_diff.h"
#include <string>
#include <vector>

namespace nori::bench {

/// \brief What to render and how often.
struct RenderCompareSettings {
    std::string scene;      ///< Nori scene file
    int spp = 0;            ///< samples per pixel (0: the scene's sampler)
    int threads = 0;        ///< render threads (0: all cores; 1: a plain loop)
    int repeats = 3;        ///< timed renders per accelerator, interleaved
    bool embreeRobust = false;
    std::string imagesDir;  ///< if set: octree.exr/png, embree.exr/png and diff.png go there
};

/// \brief One accelerator's renders of the scene.
struct RenderRun {
    std::string accel;              ///< the accel's toString()
    double buildMs = 0.0;
    double renderMs = 0.0;          ///< median of samplesMs
    std::vector<double> samplesMs;  ///< every timed render, in order
    uint64_t rays = 0;              ///< rays traced by one render
};

/// \brief The result of the full-render mode for one scene.
struct RenderComparison {
    std::string scene, integrator;
    int width = 0, height = 0, spp = 0, threads = 0, repeats = 0;
    double loadMs = 0.0;       ///< loading the scene once (parse + meshes), without the accel build
    RenderRun octree, embree;  ///< "octree" is the scene's own accel (the octree unless it names another)
    /// \brief Embree's median render time over the octree's (> 1: the octree renders faster).
    double ratioVsEmbree = 0.0;
    ImageDiff diff;            ///< the Embree render against the octree render
    bool repeatsIdentical = true;  ///< every repeat reproduced its accel's first image bit for bit
};

/// \brief Loads the scene twice (its own accel; `embree`), renders each `repeats` times
/// alternating Embree and the octree with the same block seeds, and compares the images.
class RenderCompare {
public:
    static RenderComparison run(const RenderCompareSettings &settings);
};

} // namespace nori::bench
