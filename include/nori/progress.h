/// \file progress.h
/// \brief Progress display on stderr: a bar on a terminal, sparse lines otherwise.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace nori {

/// \brief Thread-safe progress over a known number of steps.
class ProgressReporter {
public:
    /// \brief \p enabled false makes every call a no-op (-q).
    ProgressReporter(const std::string &label, long total, bool enabled);
    /// \brief Ends a bar left open (an error unwound the render), so the message starts on a new line.
    ~ProgressReporter();
    /// \brief Record \p steps more completed steps.
    void advance(long steps = 1);
    /// \brief Print the final state and end the line.
    void finish();

private:
    void draw(long done, bool final);

    std::string m_label;
    long m_total;
    bool m_enabled;
    bool m_terminal;
    std::atomic<long> m_done{0};
    std::mutex m_mutex;
    int m_lastDecile = -1;
    bool m_lineOpen = false;  ///< a bar is drawn and its line not ended
    std::chrono::steady_clock::time_point m_start, m_lastDraw;
};

} // namespace nori
