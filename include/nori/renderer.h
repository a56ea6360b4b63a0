/// \file renderer.h
/// \brief Block-based image renderer, single-threaded or on oneTBB.
#pragma once

#include <nori/bitmap.h>
#include <nori/block_exchange.h>
#include <atomic>
#include <vector>

namespace nori {

class Scene;

/// \brief How to render.
struct RenderSettings {
    int threads = 0;                             ///< 1: a plain loop; otherwise oneTBB
    bool progress = true;                        ///< progress display on stderr
    const std::atomic<bool> *cancel = nullptr;   ///< set (e.g. by SIGINT) to stop after blocks in flight
    BlockExchange *exchange = nullptr;           ///< shares the blocks with other processes; nullptr: render them all here
};

/// \brief What a render produced.
struct RenderResult {
    Bitmap image;
    bool complete = false;      ///< false if cancelled
    int blocksRendered = 0;
    int blockCount = 0;
    uint64_t rays = 0;          ///< rays traced: closestHitRays + shadowRays
    uint64_t cameraRays = 0;    ///< camera rays generated (one per sample; integrators trace each as a closest hit)
    uint64_t closestHitRays = 0;///< closest-hit queries (camera rays and bounces)
    uint64_t shadowRays = 0;    ///< any-hit queries (shadow rays)
    uint64_t droppedSamples = 0;///< non-finite samples left out of the image
    double milliseconds = 0.0;
    std::vector<RankShare> ranks;///< per process, rank by rank, when an exchange shared the render (else empty)
};

/// \brief Renders a scene in 32x32 blocks. Each block has its own sampler seeded by the
/// block index, and blocks are merged in index order, so the image is bit-identical for
/// any thread count.
class BlockRenderer {
public:
    explicit BlockRenderer(const Scene &scene) : m_scene(scene) {}
    RenderResult render(const RenderSettings &settings) const;

private:
    const Scene &m_scene;
};

} // namespace nori
