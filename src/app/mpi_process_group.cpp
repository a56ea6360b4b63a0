/// \file mpi_process_group.cpp
/// \brief ProcessGroup over MPI (NORI_MPI on): MPI_Init under a launcher, agreement on errors,
/// the block exchange of each rank, and a quiet MPI_Finalize.
#include "process_group.h"
#include "render/mpi_dispatcher.h"
#include "render/mpi_protocol.h"
#include "render/mpi_worker.h"
#include <mpi.h>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <fmt/format.h>
#include <thread>
#include <vector>

namespace nori {

namespace {

/// Whether an MPI launcher (mpirun, srun, ...) started this process. A plain `nori` never calls
/// MPI_Init: it stays exactly the single-process program, without MPI's start-up cost.
bool launchedByMpi() {
    for (const char *name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
        if (std::getenv(name)) return true;
    return false;
}

class MpiProcessGroup final : public ProcessGroup {
public:
    MpiProcessGroup() {
        MPI_Comm_dup(MPI_COMM_WORLD, &m_comm);
        MPI_Comm_rank(m_comm, &m_rank);
        MPI_Comm_size(m_comm, &m_size);
    }

    ~MpiProcessGroup() override {
        // Ranks finish at different times (rank 0 still writes the image): the others wait in
        // a barrier tested every millisecond, not in MPI_Finalize's spinning one.
        MPI_Request barrier;
        MPI_Ibarrier(m_comm, &barrier);
        mpi::waitSleeping(barrier);
        MPI_Comm_free(&m_comm);
        MPI_Finalize();
    }

    int rank() const override { return m_rank; }
    int size() const override { return m_size; }

    std::optional<std::string> agree(const std::optional<std::string> &error, const Fingerprint &fingerprint) override {
        // Rank 0 learns who failed and every fingerprint, decides, and tells everyone.
        std::vector<int64_t> mine = {error ? 1 : 0};
        mine.insert(mine.end(), fingerprint.begin(), fingerprint.end());
        const int fields = int(mine.size());
        std::vector<int64_t> all(m_rank == 0 ? size_t(fields) * size_t(m_size) : 0);
        MPI_Request request;
        MPI_Igather(mine.data(), fields, MPI_INT64_T, all.data(), fields, MPI_INT64_T, 0, m_comm, &request);
        mpi::waitSleeping(request);
        // The verdict: -1 all well; r >= 0 rank r failed first; -2 - r rank r renders another image.
        int verdict = -1;
        if (m_rank == 0) {
            for (int r = 0; r < m_size && verdict == -1; ++r)
                if (all[size_t(r) * size_t(fields)] != 0) verdict = r;
            for (int r = 1; r < m_size && verdict == -1; ++r)
                if (!std::equal(all.begin() + r * fields + 1, all.begin() + (r + 1) * fields, all.begin() + 1))
                    verdict = -2 - r;
        }
        MPI_Ibcast(&verdict, 1, MPI_INT, 0, m_comm, &request);
        mpi::waitSleeping(request);
        if (verdict == -1) return std::nullopt;
        if (verdict <= -2) {
            if (m_rank != 0) return std::string();
            const int r = -2 - verdict;
            auto describe = [&](int rank) {
                const int64_t *f = &all[size_t(rank) * size_t(fields) + 1];
                return fmt::format("{}x{} at {} spp in {} blocks", f[0], f[1], f[2], f[3]);
            };
            return fmt::format("rank {} renders {}, rank 0 {}: every rank must load the same scene with the same "
                               "options", r, describe(r), describe(0));
        }
        if (verdict == 0) return m_rank == 0 ? *error : std::string();
        // The first failing rank is not rank 0: its message travels to rank 0.
        if (m_rank == verdict) {
            MPI_Send(error->data(), int(error->size()), MPI_CHAR, 0, 0, m_comm);
            return std::string();
        }
        if (m_rank != 0) return std::string();
        MPI_Status status;
        for (int arrived = 0; !arrived;) {
            MPI_Iprobe(verdict, 0, m_comm, &arrived, &status);
            if (!arrived) std::this_thread::sleep_for(mpi::PollInterval);
        }
        int length = 0;
        MPI_Get_count(&status, MPI_CHAR, &length);
        std::string message(size_t(length), '\0');
        MPI_Recv(message.data(), length, MPI_CHAR, verdict, 0, m_comm, MPI_STATUS_IGNORE);
        return fmt::format("{} (on rank {} of {})", message, verdict, m_size);
    }

    std::unique_ptr<BlockExchange> exchange(int threads, const std::atomic<bool> *cancel) override {
        if (m_rank == 0) return std::make_unique<MpiDispatcher>(m_comm, cancel);
        return std::make_unique<MpiWorker>(m_comm, threads, cancel);
    }

    [[noreturn]] void abort(const std::string &message) override {
        std::fprintf(stderr, "nori: %s (on rank %d of %d)\n", message.c_str(), m_rank, m_size);
        std::fflush(stderr);
        MPI_Abort(MPI_COMM_WORLD, 1);
        std::_Exit(1);
    }

private:
    MPI_Comm m_comm = MPI_COMM_NULL;
    int m_rank = 0, m_size = 1;
};

} // namespace

std::unique_ptr<ProcessGroup> ProcessGroup::join(int &argc, char **&argv) {
    if (!launchedByMpi()) return nullptr;
    // The render threads never call MPI; one communication thread per rank does, and the main
    // thread before and after it.
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided);
    if (provided < MPI_THREAD_SERIALIZED) {
        std::fprintf(stderr, "nori: this MPI library cannot be used from several threads\n");
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    return std::make_unique<MpiProcessGroup>();
}

} // namespace nori
