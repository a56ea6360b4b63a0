/// \file block_exchange.h
/// \brief The interface through which several processes (MPI ranks) share the blocks of one image.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace nori {

class BlockGenerator;
class ImageBlock;
class ReconstructionFilter;

/// \brief What one rendered block traced and dropped.
struct BlockTally {
    uint64_t cameraRays = 0;     ///< one per sample
    uint64_t closestHitRays = 0; ///< closest-hit queries (camera rays and bounces)
    uint64_t shadowRays = 0;     ///< any-hit queries
    uint64_t droppedSamples = 0; ///< non-finite samples left out of the block
};

/// \brief One process's share of a render split across processes (MPI ranks).
struct RankShare {
    int blocks = 0;
    uint64_t cameraRays = 0, closestHitRays = 0, shadowRays = 0;
    /// \brief Count \p tally as one more block of this process.
    void add(const BlockTally &tally) {
        ++blocks;
        cameraRays += tally.cameraRays;
        closestHitRays += tally.closestHitRays;
        shadowRays += tally.shadowRays;
    }
};

/// \brief Shares the blocks of one image among several processes (over MPI: src/render/mpi_*).
/// The renderer claims block indices from it instead of walking them all, and hands it every
/// block it finished; the process that writes the image receives all blocks through the merge
/// function given to start(), which adds them in block-index order, so the image is the same
/// bytes as a single-process render.
class BlockExchange {
public:
    /// Adds a finished block to this process's image; thread-safe.
    using Merge = std::function<void(int index, ImageBlock &&block, const BlockTally &tally)>;

    virtual ~BlockExchange() = default;
    /// \brief Before the first claim(): the image's tiling, the filter (for blocks received
    /// from other processes) and the merge function (called only on the merging process).
    virtual void start(const BlockGenerator &generator, const ReconstructionFilter *filter, Merge merge) = 0;
    /// \brief The next block this process should render; false when none is left or the render
    /// was cancelled on any process. Thread-safe; may wait for work to arrive.
    virtual bool claim(int &index) = 0;
    /// \brief A block this process rendered. Thread-safe.
    virtual void deliver(int index, ImageBlock &&block, const BlockTally &tally) = 0;
    /// \brief After this process's threads stopped: wait until every block has been merged, or,
    /// when the render was cancelled, stop merging at once (no merge call follows either way).
    virtual void finish() = 0;
    /// \brief The shares of the processes, rank by rank (on the merging process, after finish()).
    virtual std::vector<RankShare> shares() const = 0;
};

} // namespace nori
