/// \file mpi_worker.h
/// \brief The side of an MPI render on ranks other than 0: asks rank 0 for blocks, sends them back.
#pragma once

#include <nori/block_exchange.h>
#include <mpi.h>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <list>
#include <mutex>
#include <thread>
#include <vector>

namespace nori {

/// \brief The exchange of a rank other than 0. A communication thread keeps a queue of block
/// indices from rank 0, one block per render thread ahead (so a render thread does not wait for
/// the network, and few blocks are left queued here when the image runs out), and sends each
/// finished block to rank 0. When blocks take less time than a request's round trip (about a
/// millisecond: both sides poll) and a thread finds the queue empty, the queue grows (doubling,
/// up to MaxDepthPerThread blocks per thread). The render threads only touch queue and outbox.
///
/// It ends after rank 0 answered "no more blocks", or after a Stop from rank 0 or a signal
/// here (\p cancel): the blocks in flight are rendered and sent, then a goodbye, which tells
/// rank 0 whether this rank was interrupted.
class MpiWorker final : public BlockExchange {
public:
    /// \p threads: render threads of this process (the queue's depth); \p cancel: the signal flag.
    MpiWorker(MPI_Comm comm, int threads, const std::atomic<bool> *cancel);
    /// \brief The deepest queue: blocks asked for ahead, per render thread.
    static constexpr int MaxDepthPerThread = 16;
    ~MpiWorker() override;

    void start(const BlockGenerator &generator, const ReconstructionFilter *filter, Merge merge) override;
    bool claim(int &index) override;
    void deliver(int index, ImageBlock &&block, const BlockTally &tally) override;
    void finish() override;
    std::vector<RankShare> shares() const override { return {}; }

private:
    void communicate();           ///< the communication thread
    bool poll();                  ///< one round of it; true if anything happened

    MPI_Comm m_comm;
    int m_threads;
    int m_depth;                  ///< blocks to keep queued (guarded by m_mutex)
    const std::atomic<bool> *m_cancel;

    std::mutex m_mutex;           ///< guards the fields below
    std::condition_variable m_work;    ///< render threads wait here for indices
    std::condition_variable m_wake;    ///< the communication thread waits here
    std::deque<int> m_queue;      ///< indices from rank 0 not yet claimed
    std::vector<std::vector<char>> m_outbox;   ///< finished blocks not yet sent
    bool m_noMore = false;        ///< rank 0 has no more blocks, or said Stop, or a signal came
    bool m_threadsDone = false;   ///< finish() was called

    // Owned by the communication thread.
    bool m_asking = false;        ///< a Request is out, its Assign not yet received
    int m_wanted = 0;
    std::vector<int> m_assigned;
    MPI_Request m_askSend = MPI_REQUEST_NULL, m_askReceive = MPI_REQUEST_NULL;
    struct Sending {
        std::vector<char> bytes;
        MPI_Request request = MPI_REQUEST_NULL;
    };
    std::list<Sending> m_sending; ///< blocks on their way (the buffers must live until sent)
    bool m_interrupted = false;

    std::thread m_thread;
};

} // namespace nori
