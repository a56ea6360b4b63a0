/// \file mpi_dispatcher.cpp
/// \brief MpiDispatcher: the block counter, the answers to the workers and the merge on rank 0.
#include "mpi_dispatcher.h"
#include "block_message.h"
#include "mpi_protocol.h"
#include <algorithm>
#include <cstdio>
#include <cstring>

namespace nori {

MpiDispatcher::MpiDispatcher(MPI_Comm comm, const std::atomic<bool> *cancel) : m_comm(comm), m_cancel(cancel) {
    MPI_Comm_size(comm, &m_size);
}

MpiDispatcher::~MpiDispatcher() {
    if (m_thread.joinable()) m_thread.join();
}

void MpiDispatcher::start(const BlockGenerator &generator, const ReconstructionFilter *filter, Merge merge) {
    m_generator = &generator;
    m_filter = filter;
    m_merge = std::move(merge);
    m_said.assign(size_t(m_size), false);
    m_told.assign(size_t(m_size), false);
    m_shares.assign(size_t(m_size), RankShare());
    m_thread = std::thread([this] { serve(); });
}

bool MpiDispatcher::takeIndex(int &index) {
    // Look first, so that threads polling an exhausted counter do not keep growing it.
    if (m_next.load(std::memory_order_relaxed) >= m_generator->blockCount()) return false;
    const int claimed = m_next.fetch_add(1, std::memory_order_relaxed);
    if (claimed >= m_generator->blockCount()) return false;
    index = claimed;
    return true;
}

bool MpiDispatcher::claim(int &index) {
    if (m_stopped.load() || (m_cancel && m_cancel->load())) return false;
    return takeIndex(index);
}

void MpiDispatcher::deliver(int index, ImageBlock &&block, const BlockTally &tally) {
    // Under the lock, so that no merge runs after finish() gave the image away.
    std::lock_guard<std::mutex> lock(m_mutex);
    if (!m_merging) return;
    m_shares[0].add(tally);
    m_merge(index, std::move(block), tally);
}

void MpiDispatcher::finish() {
    std::unique_lock<std::mutex> lock(m_mutex);
    // A signal here is seen by the communication thread only at its next poll: look at it too.
    while (!m_served && !m_stopped.load() && !(m_cancel && m_cancel->load()))
        m_changed.wait_for(lock, mpi::PollInterval);
    if (m_served) {
        lock.unlock();
        m_thread.join();
        return;
    }
    // Cancelled: the image is written from what is here; later blocks are only drained.
    m_merging = false;
}

std::vector<RankShare> MpiDispatcher::shares() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_shares;
}

void MpiDispatcher::stopEveryone() {
    m_stopped.store(true);
    for (int rank = 1; rank < m_size; ++rank)
        if (!m_said[size_t(rank)] && !m_told[size_t(rank)]) {
            MPI_Send(nullptr, 0, MPI_BYTE, rank, mpi::Stop, m_comm);
            m_told[size_t(rank)] = true;
        }
    std::lock_guard<std::mutex> lock(m_mutex);
    m_changed.notify_all();
}

void MpiDispatcher::serve() {
    try {
        while (m_byes < m_size - 1) {
            if (!m_stopped.load() && m_cancel && m_cancel->load()) stopEveryone();
            bool busy = false;
            for (int pending = 1; pending;) {
                MPI_Status status;
                MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, m_comm, &pending, &status);
                if (pending) {
                    handle(status);
                    busy = true;
                }
            }
            if (!busy && m_byes < m_size - 1) std::this_thread::sleep_for(mpi::PollInterval);
        }
    } catch (const std::exception &e) {
        // A malformed message means the processes disagree about the image: nothing to save.
        std::fprintf(stderr, "nori: internal error: %s\n", e.what());
        std::fflush(stderr);
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    std::lock_guard<std::mutex> lock(m_mutex);
    m_served = true;
    m_changed.notify_all();
}

void MpiDispatcher::handle(const MPI_Status &status) {
    int bytes = 0;
    MPI_Get_count(&status, MPI_BYTE, &bytes);
    m_buffer.resize(size_t(std::max(bytes, 1)));
    const int source = status.MPI_SOURCE;
    MPI_Recv(m_buffer.data(), bytes, MPI_BYTE, source, status.MPI_TAG, m_comm, MPI_STATUS_IGNORE);
    switch (status.MPI_TAG) {
    case mpi::Request: {
        int wanted = 0;
        if (bytes != int(sizeof(int))) throw NoriException("malformed request from rank {}", source);
        std::memcpy(&wanted, m_buffer.data(), sizeof(int));
        std::vector<int> indices;
        for (int index; !m_stopped.load() && int(indices.size()) < std::clamp(wanted, 1, 4096) && takeIndex(index);)
            indices.push_back(index);
        // The worker posted its receive before asking: a few indices go eagerly, a long list
        // (deep queues of many threads) waits at most for the worker's next poll.
        MPI_Send(indices.data(), int(indices.size()), MPI_INT, source, mpi::Assign, m_comm);
        break;
    }
    case mpi::Block: {
        // The tiling and the filter belong to the render, which may have ended (cancelled):
        // look at the block only while merging, under the lock that finish() takes.
        std::lock_guard<std::mutex> lock(m_mutex);
        if (!m_merging) break;
        int index = 0;
        BlockTally tally;
        ImageBlock block = BlockMessage::decode(m_buffer.data(), size_t(bytes), *m_generator, m_filter, index, tally);
        m_shares[size_t(source)].add(tally);
        m_merge(index, std::move(block), tally);
        break;
    }
    case mpi::Bye: {
        int interrupted = 0;
        if (bytes != int(sizeof(int))) throw NoriException("malformed goodbye from rank {}", source);
        std::memcpy(&interrupted, m_buffer.data(), sizeof(int));
        m_said[size_t(source)] = true;
        ++m_byes;
        if (interrupted && !m_stopped.load()) {
            m_remoteInterrupt.store(true);
            stopEveryone();
        }
        break;
    }
    default:
        throw NoriException("unexpected message (tag {}) from rank {}", status.MPI_TAG, source);
    }
}

} // namespace nori
