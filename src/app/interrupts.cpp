/// \file interrupts.cpp
/// \brief Interrupts: async-signal-safe handlers over a few atomics.
#include "interrupts.h"
#include <nori/atomic_file.h>
#include <csignal>
#include <cstdlib>

namespace nori {

namespace {

std::atomic<bool> g_cancelled{false};
std::atomic<int> g_signal{0};
std::atomic<bool> g_committing{false};

extern "C" void onSignal(int sig) {
    int none = 0;
    g_signal.compare_exchange_strong(none, sig);
    if (!g_cancelled.exchange(true)) return;
    // A second signal: the user really wants out, but never with half of the outputs renamed.
    if (g_committing.load()) return;
    AtomicFile::removeTemporariesNow();
    std::_Exit(128 + g_signal.load());
}

} // namespace

void Interrupts::install() {
    struct sigaction action {};
    action.sa_handler = onSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &action, nullptr);
}

std::atomic<bool> &Interrupts::cancelled() { return g_cancelled; }

int Interrupts::signal() { return g_signal.load(); }

void Interrupts::setCommitting(bool committing) { g_committing.store(committing); }

} // namespace nori
