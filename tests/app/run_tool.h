/// \file run_tool.h
/// \brief Runs one of the project's executables and collects its exit status, stdout and stderr.
#pragma once

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <spawn.h>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char **environ;

namespace nori {

/// \brief How a tool ended and what it printed.
struct ToolRun {
    bool exited = false;  ///< false: killed by a signal
    int code = -1;        ///< exit status, or the signal number
    std::string out, err;

    /// \brief Number of lines on stderr.
    long errLines() const { return long(std::count(err.begin(), err.end(), '\n')); }
};

/// \brief Where and how to run it.
struct ToolSetup {
    std::string cwd;                    ///< working folder (empty: the test's)
    std::vector<std::string> env;       ///< extra NAME=VALUE entries
    bool limitAddressSpace = false;     ///< 1 GiB of address space (not under sanitizers)
};

/// \brief The full path of a tool built at the top of the build folder (e.g. "nori").
inline std::string toolPath(const std::string &name) { return std::string(NORI_BINARY_DIR) + "/" + name; }

/// \brief Run \p binary with \p args (stdin /dev/null) and wait for it.
inline ToolRun runTool(const std::string &binary, const std::vector<std::string> &args, const ToolSetup &setup = {}) {
    char outName[] = "/tmp/nori-tool-out-XXXXXX", errName[] = "/tmp/nori-tool-err-XXXXXX";
    int outFd = mkstemp(outName), errFd = mkstemp(errName);
    if (outFd < 0 || errFd < 0) throw std::runtime_error("mkstemp failed");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, outFd, 1);
    posix_spawn_file_actions_adddup2(&actions, errFd, 2);
    if (!setup.cwd.empty()) posix_spawn_file_actions_addchdir_np(&actions, setup.cwd.c_str());
    std::vector<std::string> argvStrings = {binary};
    argvStrings.insert(argvStrings.end(), args.begin(), args.end());
    std::vector<char *> argv;
    for (auto &a : argvStrings) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> envStrings;
    for (char **e = environ; *e; ++e) envStrings.push_back(*e);
    envStrings.insert(envStrings.end(), setup.env.begin(), setup.env.end());
    std::vector<char *> envp;
    for (auto &e : envStrings) envp.push_back(e.data());
    envp.push_back(nullptr);
    // The limit is inherited through spawn: a few bytes of bad input must not make a tool reserve
    // gigabytes. Sanitizers reserve huge shadow mappings: no limit there.
    struct rlimit saved {};
    getrlimit(RLIMIT_AS, &saved);
#if !defined(__SANITIZE_ADDRESS__)
    if (setup.limitAddressSpace) {
        struct rlimit limited = saved;
        limited.rlim_cur = std::min<rlim_t>(saved.rlim_cur, rlim_t(1) << 30);
        setrlimit(RLIMIT_AS, &limited);
    }
#endif
    pid_t pid = 0;
    int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
    setrlimit(RLIMIT_AS, &saved);
    posix_spawn_file_actions_destroy(&actions);
    close(outFd);
    close(errFd);
    ToolRun result;
    auto slurp = [](const char *name) {
        std::ifstream in(name, std::ios::binary);
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        unlink(name);
        return text;
    };
    if (rc != 0) {
        unlink(outName);
        unlink(errName);
        throw std::runtime_error(std::string("posix_spawn failed: ") + std::strerror(rc));
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) throw std::runtime_error("waitpid failed");
    result.exited = WIFEXITED(status);
    result.code = result.exited ? WEXITSTATUS(status) : WTERMSIG(status);
    result.out = slurp(outName);
    result.err = slurp(errName);
    return result;
}

} // namespace nori
