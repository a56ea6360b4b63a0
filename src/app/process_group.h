/// \file process_group.h
/// \brief The processes that render one image together: one alone, or the ranks of `mpirun`.
#pragma once

#include <nori/block_exchange.h>
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace nori {

/// \brief The MPI ranks started by `mpirun -np N nori ...` (see src/app/mpi_process_group.cpp).
/// Every rank parses the same command line and loads the scene; rank 0 alone prints and writes.
class ProcessGroup {
public:
    /// \brief What must be the same on every rank for the blocks to fit one image: width,
    /// height, samples per pixel and block count.
    using Fingerprint = std::array<int64_t, 4>;

    /// \brief Join the group when an MPI launcher started this process (MPI_Init); nullptr when
    /// it runs alone, or when nori was built without MPI (NORI_MPI off).
    static std::unique_ptr<ProcessGroup> join(int &argc, char **&argv);

    /// \brief Waits for every rank, without spinning, and leaves MPI (MPI_Finalize).
    virtual ~ProcessGroup() = default;

    virtual int rank() const = 0;
    virtual int size() const = 0;

    /// \brief Collective, after every rank loaded the scene: each passes its error message (or
    /// nothing) and its fingerprint. If some rank failed, or a rank's fingerprint differs from
    /// rank 0's, every rank gets a message back: on rank 0 the text to print once (the first
    /// failing rank's own message, naming that rank if it is not 0), elsewhere an empty string.
    virtual std::optional<std::string> agree(const std::optional<std::string> &error, const Fingerprint &fingerprint) = 0;

    /// \brief How this rank takes part in the render: rank 0 hands out and merges, the others
    /// ask and send. \p threads: render threads of this rank; \p cancel: the signal flag.
    virtual std::unique_ptr<BlockExchange> exchange(int threads, const std::atomic<bool> *cancel) = 0;

    /// \brief After an error that the other ranks cannot learn of in time (during the render):
    /// print \p message (one line) and end every rank (MPI_Abort).
    [[noreturn]] virtual void abort(const std::string &message) = 0;
};

} // namespace nori
