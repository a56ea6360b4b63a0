/// \file mpi_protocol.h
/// \brief The messages between rank 0 (MpiDispatcher) and the other ranks (MpiWorker) during a
/// render, and how both wait for them without spinning.
#pragma once

#include <mpi.h>
#include <chrono>
#include <thread>

namespace nori::mpi {

/// Message tags, all on one private communicator (a duplicate of MPI_COMM_WORLD).
enum Tag : int {
    /// worker -> 0: one int, how many more block indices the worker wants.
    Request = 1,
    /// 0 -> worker: the answer to a Request, ints, block indices; none means "no more work".
    /// Every Request gets exactly one Assign.
    Assign = 2,
    /// worker -> 0: one finished block (BlockMessage bytes).
    Block = 3,
    /// worker -> 0: the worker's last message; one int, nonzero if it was interrupted.
    Bye = 4,
    /// 0 -> worker: the render was cancelled; stop after the blocks in flight. No payload.
    Stop = 5,
};

/// How long a communication thread sleeps when it found nothing to do. Open MPI's blocking
/// calls spin on a core; the render threads need those cores, and a worker asks for its next
/// block while it still has one queued, so a millisecond of latency costs no render time.
constexpr std::chrono::microseconds PollInterval(1000);

/// \brief Wait for \p request, testing it every PollInterval instead of spinning.
inline void waitSleeping(MPI_Request &request) {
    for (int done = 0;;) {
        MPI_Test(&request, &done, MPI_STATUS_IGNORE);
        if (done) return;
        std::this_thread::sleep_for(PollInterval);
    }
}

} // namespace nori::mpi
