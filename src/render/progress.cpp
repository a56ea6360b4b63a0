/// \file progress.cpp
/// \brief Progress display on stderr: a bar on a terminal, sparse lines otherwise (implementation).
#include <nori/progress.h>
#include <cstdio>
#include <unistd.h>

namespace nori {

ProgressReporter::ProgressReporter(const std::string &label, long total, bool enabled)
    : m_label(label), m_total(total > 0 ? total : 1), m_enabled(enabled), m_terminal(isatty(STDERR_FILENO) != 0),
      m_start(std::chrono::steady_clock::now()), m_lastDraw(m_start) {}

ProgressReporter::~ProgressReporter() {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_lineOpen) std::fputc('\n', stderr);
}

void ProgressReporter::advance(long steps) {
    long done = m_done.fetch_add(steps) + steps;
    if (!m_enabled) return;
    std::lock_guard<std::mutex> lock(m_mutex);
    draw(done, false);
}

void ProgressReporter::finish() {
    if (!m_enabled) return;
    std::lock_guard<std::mutex> lock(m_mutex);
    draw(m_done.load(), true);
}

void ProgressReporter::draw(long done, bool final) {
    auto now = std::chrono::steady_clock::now();
    double elapsed = std::chrono::duration<double>(now - m_start).count();
    double fraction = double(done) / double(m_total);
    if (m_terminal) {
        // Redraw at most 10 times a second: a terminal is slow and the bar is for humans.
        if (!final && now - m_lastDraw < std::chrono::milliseconds(100)) return;
        m_lastDraw = now;
        const int width = 40;
        int filled = int(fraction * width + 0.5);
        std::string bar(size_t(filled), '=');
        bar.resize(width, ' ');
        double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
        std::fprintf(stderr, "\r%s [%s] %5.1f%% %6.1fs elapsed, %6.1fs left ", m_label.c_str(), bar.c_str(),
                     100.0 * fraction, elapsed, eta);
        if (final) std::fputc('\n', stderr);
        m_lineOpen = !final;
    } else {
        // Logs get one line per 10%.
        int decile = int(fraction * 10.0);
        if (decile == m_lastDecile && !final) return;
        if (final && decile == m_lastDecile) return;
        m_lastDecile = decile;
        std::fprintf(stderr, "%s: %3d%% (%.1fs)\n", m_label.c_str(), decile * 10, elapsed);
    }
    std::fflush(stderr);
}

} // namespace nori
