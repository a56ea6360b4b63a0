/// \file mpi_worker.cpp
/// \brief MpiWorker: the queue of block indices and the outbox of a rank other than 0.
#include "mpi_worker.h"
#include "block_message.h"
#include "mpi_protocol.h"
#include <algorithm>

namespace nori {

MpiWorker::MpiWorker(MPI_Comm comm, int threads, const std::atomic<bool> *cancel)
    : m_comm(comm), m_threads(std::clamp(threads, 1, 256)), m_depth(m_threads), m_cancel(cancel) {}

MpiWorker::~MpiWorker() {
    if (m_thread.joinable()) {
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_threadsDone = true;
        }
        m_wake.notify_all();
        m_thread.join();
    }
}

void MpiWorker::start(const BlockGenerator &, const ReconstructionFilter *, Merge) {
    m_assigned.resize(size_t(MaxDepthPerThread * m_threads));
    m_thread = std::thread([this] { communicate(); });
}

bool MpiWorker::claim(int &index) {
    std::unique_lock<std::mutex> lock(m_mutex);
    // A thread that finds the queue empty waited for the network: keep more blocks queued.
    if (m_queue.empty() && !m_noMore) m_depth = std::min(2 * m_depth, MaxDepthPerThread * m_threads);
    m_work.wait(lock, [&] { return !m_queue.empty() || m_noMore; });
    if (m_queue.empty()) return false;
    index = m_queue.front();
    m_queue.pop_front();
    m_wake.notify_one(); // the queue shrank: time to ask for more
    return true;
}

void MpiWorker::deliver(int index, ImageBlock &&block, const BlockTally &tally) {
    std::vector<char> bytes = BlockMessage::encode(index, block, tally);
    std::lock_guard<std::mutex> lock(m_mutex);
    m_outbox.push_back(std::move(bytes));
    m_wake.notify_one();
}

void MpiWorker::finish() {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_threadsDone = true;
    }
    m_wake.notify_all();
    if (m_thread.joinable()) m_thread.join();
}

void MpiWorker::communicate() {
    for (;;) {
        if (poll()) continue;
        std::unique_lock<std::mutex> lock(m_mutex);
        // Done when the threads are, every block is sent and no answer is outstanding.
        if (m_threadsDone && m_outbox.empty() && m_sending.empty() && !m_asking) break;
        m_wake.wait_for(lock, mpi::PollInterval);
    }
    int interrupted = m_interrupted ? 1 : 0;
    MPI_Send(&interrupted, 1, MPI_INT, 0, mpi::Bye, m_comm);
}

bool MpiWorker::poll() {
    bool busy = false;
    std::vector<std::vector<char>> outbox;
    bool stopNow = false, ask = false;
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        outbox.swap(m_outbox);
        if (!m_noMore && m_cancel && m_cancel->load()) {
            m_interrupted = true;
            stopNow = true;
        }
        if (!m_noMore && !stopNow && !m_asking && int(m_queue.size()) < m_depth) {
            m_wanted = m_depth - int(m_queue.size());
            ask = true;
        }
    }
    // A Stop from rank 0: the render was cancelled elsewhere.
    int stop = 0;
    MPI_Iprobe(0, mpi::Stop, m_comm, &stop, MPI_STATUS_IGNORE);
    if (stop) {
        MPI_Recv(nullptr, 0, MPI_BYTE, 0, mpi::Stop, m_comm, MPI_STATUS_IGNORE);
        stopNow = true;
        ask = false;
    }
    if (stopNow) {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_noMore = true;
        m_queue.clear();
        m_work.notify_all();
        busy = true;
    }
    for (std::vector<char> &bytes : outbox) {
        m_sending.push_back(Sending{std::move(bytes)});
        Sending &sending = m_sending.back();
        MPI_Isend(sending.bytes.data(), int(sending.bytes.size()), MPI_BYTE, 0, mpi::Block, m_comm, &sending.request);
        busy = true;
    }
    for (auto it = m_sending.begin(); it != m_sending.end();) {
        int done = 0;
        MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);
        it = done ? m_sending.erase(it) : std::next(it);
    }
    if (ask) {
        MPI_Isend(&m_wanted, 1, MPI_INT, 0, mpi::Request, m_comm, &m_askSend);
        MPI_Irecv(m_assigned.data(), int(m_assigned.size()), MPI_INT, 0, mpi::Assign, m_comm, &m_askReceive);
        m_asking = true;
        busy = true;
    }
    if (m_asking) {
        int sent = 0, received = 0;
        MPI_Status status;
        MPI_Test(&m_askSend, &sent, MPI_STATUS_IGNORE);
        if (sent) MPI_Test(&m_askReceive, &received, &status);
        if (received) {
            int count = 0;
            MPI_Get_count(&status, MPI_INT, &count);
            std::lock_guard<std::mutex> lock(m_mutex);
            // Indices that arrive after a Stop are dropped: rank 0 no longer waits for them.
            if (!m_noMore) {
                m_queue.insert(m_queue.end(), m_assigned.begin(), m_assigned.begin() + count);
                if (count == 0) m_noMore = true;
            }
            m_work.notify_all();
            m_asking = false;
            busy = true;
        }
    }
    return busy;
}

} // namespace nori
