/// \file mpi_dispatcher.h
/// \brief Rank 0's side of an MPI render: hands out blocks, receives the finished ones, merges.
#pragma once

#include <nori/block.h>
#include <nori/block_exchange.h>
#include <mpi.h>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace nori {

/// \brief The exchange of rank 0. Its render threads claim blocks from the same counter from
/// which a communication thread answers the other ranks' requests, so blocks go to whoever is
/// free first. Blocks rendered here and blocks received from the others are merged through the
/// renderer's (ordered) merge function and counted per rank.
///
/// Cancellation: when \p cancel is set (a signal here) or another rank says it was interrupted,
/// no more blocks are handed out and every rank is told to stop. finish() then returns at once,
/// so that the partial image is written from the blocks that are here; the communication thread
/// goes on draining the others' last messages until each has said goodbye (the destructor waits).
class MpiDispatcher final : public BlockExchange {
public:
    /// \p comm: the communicator of the render (rank 0 is this process); \p cancel: the signal flag.
    MpiDispatcher(MPI_Comm comm, const std::atomic<bool> *cancel);
    ~MpiDispatcher() override;

    void start(const BlockGenerator &generator, const ReconstructionFilter *filter, Merge merge) override;
    bool claim(int &index) override;
    void deliver(int index, ImageBlock &&block, const BlockTally &tally) override;
    void finish() override;
    std::vector<RankShare> shares() const override;

    /// \brief Whether another rank reported an interruption (this rank may have had no signal).
    bool interruptedElsewhere() const { return m_remoteInterrupt.load(); }

private:
    void serve();                              ///< the communication thread
    void handle(const MPI_Status &status);     ///< one message from a worker
    void stopEveryone();                       ///< cancel: stop handing out, tell each worker
    bool takeIndex(int &index);                ///< the next unclaimed block, if any

    MPI_Comm m_comm;
    int m_size = 1;
    const std::atomic<bool> *m_cancel;
    const BlockGenerator *m_generator = nullptr;    ///< the render's; used only while m_merging
    const ReconstructionFilter *m_filter = nullptr;
    Merge m_merge;

    std::atomic<int> m_next{0};                ///< the next block to hand out
    std::atomic<bool> m_stopped{false};        ///< no more blocks: cancelled somewhere
    std::atomic<bool> m_remoteInterrupt{false};
    std::vector<bool> m_said;                  ///< per rank: said goodbye
    std::vector<bool> m_told;                  ///< per rank: was sent Stop
    int m_byes = 0;

    mutable std::mutex m_mutex;                ///< guards the fields below
    std::condition_variable m_changed;
    bool m_merging = true;                     ///< false once finish() let the image go
    bool m_served = false;                     ///< the communication thread is done
    std::vector<RankShare> m_shares;

    std::thread m_thread;
    std::vector<char> m_buffer;                ///< the message being received
};

} // namespace nori
