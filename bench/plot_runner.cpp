/// \file plot_runner.cpp
/// \brief Draws the charts by running bench/plot.py on a results JSON file (implementation).
#include "plot_runner.h"
#include <nori/common.h>
#include <cerrno>
#include <cstring>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#ifndef NORI_BENCH_PLOT_SCRIPT
#define NORI_BENCH_PLOT_SCRIPT "bench/plot.py"
#endif

namespace nori::bench {

std::string PlotRunner::scriptPath() { return NORI_BENCH_PLOT_SCRIPT; }

void PlotRunner::run(const std::string &python, const std::string &jsonPath, const std::string &outDir) {
    std::string script = scriptPath();
    if (access(script.c_str(), R_OK) != 0) throw NoriException("--plots: cannot read the plot script {}", script);
    if (access(python.c_str(), X_OK) != 0) throw NoriException("--plots: no Python interpreter at {}", python);
    std::vector<std::string> args{python, script, jsonPath, "--out", outDir};
    std::vector<char *> argv;
    for (std::string &a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = fork();
    if (pid < 0) throw NoriException("--plots: fork failed: {}", std::strerror(errno));
    if (pid == 0) {
        execv(argv[0], argv.data());
        _exit(127);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) throw NoriException("--plots: waitpid failed: {}", std::strerror(errno));
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw NoriException("--plots: {} {} failed (status {})", python, script,
                            WIFEXITED(status) ? WEXITSTATUS(status) : -1);
}

} // namespace nori::bench
