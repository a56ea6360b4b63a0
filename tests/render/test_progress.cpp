/// \file test_progress.cpp
/// \brief The progress bar on a terminal: an error that unwinds the render must not be glued
/// onto the bar's line.
#include <gtest/gtest.h>
#include <nori/progress.h>
#include <chrono>
#include <fcntl.h>
#include <pty.h>
#include <stdexcept>
#include <string>
#include <thread>
#include <unistd.h>

using namespace nori;

namespace {

/// stderr redirected to a pseudo-terminal (so that the reporter draws its bar) while alive.
class StderrOnTerminal {
public:
    StderrOnTerminal() {
        if (openpty(&m_master, &m_slave, nullptr, nullptr, nullptr) != 0) return;
        std::fflush(stderr);
        m_saved = dup(STDERR_FILENO);
        dup2(m_slave, STDERR_FILENO);
        fcntl(m_master, F_SETFL, O_NONBLOCK);
    }
    ~StderrOnTerminal() { restore(); }
    bool ok() const { return m_saved >= 0; }
    /// Restore stderr and return what was written to the terminal.
    std::string restore() {
        if (m_saved < 0) return {};
        std::fflush(stderr);
        dup2(m_saved, STDERR_FILENO);
        close(m_saved);
        m_saved = -1;
        std::string text;
        char buffer[4096];
        for (ssize_t n; (n = read(m_master, buffer, sizeof buffer)) > 0;) text.append(buffer, size_t(n));
        close(m_slave);
        close(m_master);
        return text;
    }

private:
    int m_master = -1, m_slave = -1, m_saved = -1;
};

} // namespace

TEST(Progress, BarLeftOpenByAnErrorIsEndedBeforeTheMessage) {
    StderrOnTerminal terminal;
    if (!terminal.ok()) GTEST_SKIP() << "no pseudo-terminal";
    try {
        ProgressReporter progress("Rendering", 10, true);
        std::this_thread::sleep_for(std::chrono::milliseconds(120));  // the bar redraws at most every 100 ms
        progress.advance(3);
        throw std::runtime_error("failure inside the render");
    } catch (const std::runtime_error &) {
    }
    std::fputs("nori: the error\n", stderr);
    std::string text = terminal.restore();
    ASSERT_NE(text.find("Rendering ["), std::string::npos) << text;
    // A terminal turns \n into \r\n: the message must start a line of its own.
    EXPECT_NE(text.find("\nnori: the error"), std::string::npos) << text;
    EXPECT_EQ(text.find("left nori:"), std::string::npos) << text;
}
