/// \file test_cli.cpp
/// \brief End-to-end tests of the `nori` command: outputs, statistics, help, and Ctrl-C.
#include <gtest/gtest.h>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <spawn.h>
#include <sstream>
#include <sys/wait.h>
#include <temp_dir.h>
#include <unistd.h>

extern char **environ;

using namespace nori;

namespace {

const std::string kNori = std::string(NORI_BINARY_DIR) + "/nori";
const std::string kBunnyScene = std::string(NORI_SHARED_DIR) + "/nori-scenes/pa1/bunny.xml";

/// A running `nori` whose stderr we read line by line.
class NoriProcess {
public:
    explicit NoriProcess(const std::vector<std::string> &args) {
        int fds[2];
        if (pipe(fds) != 0) throw std::runtime_error("pipe");
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
        posix_spawn_file_actions_addclose(&actions, fds[0]);
        std::vector<std::string> all = {kNori};
        all.insert(all.end(), args.begin(), args.end());
        std::vector<char *> argv;
        for (auto &a : all) argv.push_back(a.data());
        argv.push_back(nullptr);
        if (posix_spawn(&m_pid, kNori.c_str(), &actions, nullptr, argv.data(), environ) != 0)
            throw std::runtime_error("spawn");
        posix_spawn_file_actions_destroy(&actions);
        close(fds[1]);
        m_err = fdopen(fds[0], "r");
    }
    ~NoriProcess() {
        if (m_err) fclose(m_err);
    }
    /// Next line of stderr (false at end of output).
    bool readLine(std::string &line) {
        char buffer[4096];
        if (!fgets(buffer, sizeof buffer, m_err)) return false;
        line = buffer;
        m_stderr += line;
        return true;
    }
    void interrupt() { kill(m_pid, SIGINT); }
    /// Waits; returns the exit code, or -signal if it died of a signal.
    int wait() {
        std::string line;
        while (readLine(line)) {}
        int status = 0;
        waitpid(m_pid, &status, 0);
        return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
    }
    const std::string &stderrText() const { return m_stderr; }

private:
    pid_t m_pid = 0;
    FILE *m_err = nullptr;
    std::string m_stderr;
};

std::string readFile(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

TEST(Cli, HelpExitsZero) {
    NoriProcess p({"--help"});
    EXPECT_EQ(p.wait(), 0);
}

TEST(Cli, RendersBothImagesAndStatsJson) {
    if (!std::filesystem::exists(kBunnyScene)) GTEST_SKIP() << "needs " << kBunnyScene;
    TempDir dir;
    NoriProcess p({kBunnyScene, "-o", dir.file("out.exr"), "--stats-json", dir.file("stats.json"), "-t", "2"});
    ASSERT_EQ(p.wait(), 0) << p.stderrText();
    EXPECT_GT(std::filesystem::file_size(dir.file("out.exr")), 1000u);
    EXPECT_GT(std::filesystem::file_size(dir.file("out.png")), 1000u);
    std::string json = readFile(dir.file("stats.json"));
    for (const char *key : {"\"load_ms\"", "\"build_ms\"", "\"render_ms\"", "\"rays\": 589824", "\"triangles\": 2000"})
        EXPECT_NE(json.find(key), std::string::npos) << key << " missing in\n" << json;
    EXPECT_NE(p.stderrText().find("Mrays/s"), std::string::npos) << p.stderrText();
}

TEST(Cli, BadOptionGivesOneLineAndNoOutput) {
    TempDir dir;
    NoriProcess p({"--threads", "0", kBunnyScene, "-o", dir.file("out")});
    EXPECT_EQ(p.wait(), 2);  // a usage error
    EXPECT_EQ(std::count(p.stderrText().begin(), p.stderrText().end(), '\n'), 1) << p.stderrText();
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.exr")));
}

TEST(Cli, InterruptSavesPartialImageAndKeepsEarlierOutput) {
    if (!std::filesystem::exists(kBunnyScene)) GTEST_SKIP() << "needs " << kBunnyScene;
    TempDir dir;
    std::string earlier = dir.write("out.exr", "an earlier image");
    // Brute force at 16 spp: minutes of work, so the interrupt surely lands mid-render.
    NoriProcess p({kBunnyScene, "-o", dir.file("out"), "--accel", "brute", "--spp", "16", "-t", "2"});
    std::string line;
    while (p.readLine(line) && line.find("Rendering") == std::string::npos) {}
    p.interrupt();
    EXPECT_EQ(p.wait(), 130) << p.stderrText();
    EXPECT_TRUE(std::filesystem::exists(dir.file("out-partial.exr"))) << p.stderrText();
    EXPECT_EQ(readFile(earlier), "an earlier image");
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.png")));
}
