/// \file interrupts.h
/// \brief SIGINT, SIGTERM and SIGHUP while `nori` renders and writes.
#pragma once

#include <atomic>

namespace nori {

/// \brief The first signal asks to stop: the render ends after the blocks in flight (the
/// partial image is kept) and a write under way completes. A second signal ends the process at
/// once after removing every temporary output file, except while the outputs are being renamed
/// (microseconds), which always completes, so that no mixed set of outputs is left.
class Interrupts {
public:
    /// \brief Install the handlers (once, before the render).
    static void install();
    /// \brief Set by the first signal; the renderer polls it.
    static std::atomic<bool> &cancelled();
    /// \brief The first signal received (0: none).
    static int signal();
    /// \brief While true a second signal is only recorded (the renames run).
    static void setCommitting(bool committing);
    /// \brief 128 + the first signal, the shell's convention for "ended by a signal".
    static int exitStatus() { return 128 + signal(); }
};

} // namespace nori
