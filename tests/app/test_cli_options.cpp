/// \file test_cli_options.cpp
/// \brief The command-line conventions of `nori` and `nori-bench` (issue 12): GNU-style option
/// forms, --version, --, grouped --help, usage errors, options that do not apply, and a
/// --stats-json that stays valid JSON whatever the scene's file name.
#include "run_tool.h"
#include "accel/octree.h"
#include <nori/proplist.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <temp_dir.h>
#include <filesystem>
#include <fstream>

using namespace nori;
namespace fs = std::filesystem;

namespace {

const std::string kNori = toolPath("nori");
const std::string kBench = toolPath("bench/nori-bench");
const fs::path kCorpus = fs::path(NORI_SOURCE_DIR) / "tests" / "data" / "bad";

/// A folder holding the small positive-control scene (16x16, one triangle) under \p sceneName.
struct SmallScene {
    TempDir dir;
    std::string scene;
    explicit SmallScene(const std::string &sceneName = "scene.xml") {
        fs::copy_file(kCorpus / "good.xml", dir.path() / sceneName);
        fs::copy_file(kCorpus / "tri.obj", dir.path() / "tri.obj");
        scene = dir.file(sceneName);
    }
};

std::string readFile(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

} // namespace

TEST(CliOptions, ThreadsAsLongOptionWithEqualsAndAsAttachedShortOption) {
    SmallScene s;
    for (const std::vector<std::string> &threads : {std::vector<std::string>{"--threads=2"}, {"-t2"}, {"-t", "2"}}) {
        SCOPED_TRACE(threads.front());
        std::vector<std::string> args = threads;
        for (const char *a : {"-q", "--stats-json"}) args.push_back(a);
        args.push_back(s.dir.file("stats.json"));
        args.push_back(s.scene);
        ToolRun r = runTool(kNori, args);
        ASSERT_TRUE(r.exited);
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_EQ(nlohmann::json::parse(readFile(s.dir.file("stats.json")))["threads"], 2);
        EXPECT_TRUE(fs::exists(s.dir.file("scene.exr")));
    }
}

TEST(CliOptions, VersionNamesTheProjectVersion) {
    ToolRun r = runTool(kNori, {"--version"});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out.rfind(std::string("nori ") + NORI_PROJECT_VERSION, 0), 0u) << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    EXPECT_EQ(r.err, "");
}

TEST(CliOptions, DoubleDashBeforeASceneNameStartingWithDash) {
    SmallScene s("-scene.xml");
    ToolSetup inFolder;
    inFolder.cwd = s.dir.path().string();
    ToolRun refused = runTool(kNori, {"-q", "-scene.xml"}, inFolder);
    EXPECT_EQ(refused.code, 2) << refused.err;
    EXPECT_EQ(refused.errLines(), 1) << refused.err;
    ToolRun r = runTool(kNori, {"-q", "--", "-scene.xml"}, inFolder);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(s.dir.file("-scene.exr")));
    EXPECT_TRUE(fs::exists(s.dir.file("-scene.png")));
}

TEST(CliOptions, HelpIsGroupedAndGoesToStdout) {
    ToolRun r = runTool(kNori, {"--help"});
    EXPECT_EQ(r.code, 0);
    for (const char *heading : {"Output:", "Rendering:", "Octree (only with --accel octree", "--version", "-t,--threads"})
        EXPECT_NE(r.out.find(heading), std::string::npos) << heading << " missing in\n" << r.out;
}

// The defaults --help states for the octree are the accelerator's own (they had gone stale:
// the help said maxDepth 16 and leafSize 512, the defaults of the count rule, long after sah
// became the default with 24 and 17).
TEST(CliOptions, HelpStatesTheOctreesActualDefaults) {
    PropertyList none;
    const OctreeAccel octree(none);
    const std::string settings = octree.toString();
    ToolRun r = runTool(kNori, {"--help"});
    ASSERT_EQ(r.code, 0);
    for (const auto &[property, option] : {std::pair{"maxDepth", "--max-depth"}, std::pair{"leafSize", "--leaf-size"}}) {
        const size_t at = settings.find(std::string(property) + "=");
        ASSERT_NE(at, std::string::npos) << settings;
        const std::string value = settings.substr(at + std::string(property).size() + 1,
                                                  settings.find_first_of(",]", at) - at - std::string(property).size() - 1);
        const size_t line = r.out.find(option);
        ASSERT_NE(line, std::string::npos) << option;
        const std::string text = r.out.substr(line, r.out.find('\n', line) - line);
        EXPECT_NE(text.find("(default " + value + ";"), std::string::npos) << option << ": " << text << " (the octree: " << settings << ")";
    }
}

TEST(CliOptions, UsageErrorsAreOneLineNamingTheOptionWithStatus2) {
    SmallScene s;
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--threads=0", s.scene}, "--threads: expected an integer in [1, 1024], got '0'"},
        {{"-tx", s.scene}, "--threads"},
        {{"--spp", "1e3", s.scene}, "--spp: expected an integer in [1, 1048576], got '1e3'"},
        {{"--accel", "nope", s.scene}, "--accel: unknown value 'nope'"},
        {{"--bogus", s.scene}, "--bogus"},
        {{"-q"}, "SCENE is required"},
        {{s.scene, "--spp"}, "--spp"},
        {{"--max-depth", "33", s.scene}, "--max-depth: expected an integer in [0, 32]"},
        {{"-o", s.dir.file("x.jpg"), s.scene}, "must end in .exr or .png"},
    };
    for (const auto &[args, message] : cases) {
        SCOPED_TRACE(args.front());
        ToolRun r = runTool(kNori, args);
        EXPECT_TRUE(r.exited);
        EXPECT_EQ(r.code, 2) << r.err;
        EXPECT_EQ(r.errLines(), 1) << r.err;
        EXPECT_EQ(r.err.rfind("nori: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    }
    EXPECT_FALSE(fs::exists(s.dir.file("scene.exr")));
}

// The octree's settings mean nothing to another accelerator: say so instead of ignoring them.
TEST(CliOptions, OctreeOptionWithAnotherAccelIsRefused) {
    SmallScene s;
    for (const char *option : {"--max-depth=5", "--leaf-size=4", "--overlap=bbox", "--traversal=sorted", "--intersector=mt"}) {
        SCOPED_TRACE(option);
        ToolRun r = runTool(kNori, {"-q", "--accel", "brute", option, s.scene});
        EXPECT_EQ(r.code, 2) << r.err;
        EXPECT_EQ(r.errLines(), 1) << r.err;
        std::string name = std::string(option).substr(0, std::string(option).find('='));
        EXPECT_NE(r.err.find(name + " applies only to --accel octree"), std::string::npos) << r.err;
    }
    EXPECT_FALSE(fs::exists(s.dir.file("scene.exr")));
    // The same option with the octree is fine (the check is not a blanket refusal); depth 0 (a
    // single leaf) is in the README's range 0-32.
    ToolRun ok = runTool(kNori, {"-q", "--accel", "octree", "--max-depth=0", s.scene});
    EXPECT_EQ(ok.code, 0) << ok.err;
}

// A tab, a quote, a backslash and a newline in the scene's file name: the document stays valid JSON
// and gives the name back exactly.
TEST(CliOptions, StatsJsonIsValidForAnySceneName) {
    const std::string name = "odd\tname \"quoted\" back\\slash\nline.xml";
    SmallScene s(name);
    ToolRun r = runTool(kNori, {"-q", "--stats-json", s.dir.file("stats.json"), "-o", s.dir.file("out"), s.scene});
    ASSERT_EQ(r.code, 0) << r.err;
    nlohmann::json json;
    ASSERT_NO_THROW(json = nlohmann::json::parse(readFile(s.dir.file("stats.json"))));
    EXPECT_EQ(json["scene"], s.scene);
    EXPECT_EQ(json["width"], 16);
    EXPECT_EQ(json["complete"], true);
    EXPECT_GT(json["rays"].get<long long>(), 0);
    EXPECT_TRUE(json["load_ms"].is_number_float()) << json.dump();
}

TEST(BenchOptions, VersionAndUsageErrors) {
    if (!fs::exists(kBench)) GTEST_SKIP() << "nori-bench is not built";
    ToolRun version = runTool(kBench, {"--version"});
    EXPECT_EQ(version.code, 0);
    EXPECT_EQ(version.out.rfind(std::string("nori-bench ") + NORI_PROJECT_VERSION, 0), 0u) << version.out;
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--depths", "20,x"}, "--depths: expected an integer in [0, 64], got 'x'"},
        {{"--depths=6,6", "--quick"}, "'6' listed twice"},
        {{"--overlaps", "exact,", "--quick"}, "empty item"},
        {{"--intersectors", "fast", "--quick"}, "unknown value 'fast'"},
        {{"--default-only", "--depths", "6", "--quick"}, "--default-only excludes --depths"},
        {{"--no-brute", "--brute-rays=5", "--quick"}, "excludes"},
        {{"--python", "/bin/true", "--quick"}, "--python requires --plots"},
        {{"--mesh", "a.obj", "--scene", "b.xml"}, "excludes"},
        {{"--scene", "b.xml", "--width", "64"}, "--scene excludes --width"},
        {{"--scene", "b.xml", "--height", "64"}, "--scene excludes --height"},
        {{}, "nothing to measure"},
    };
    for (const auto &[args, message] : cases) {
        SCOPED_TRACE(message);
        ToolRun r = runTool(kBench, args);
        EXPECT_EQ(r.code, 2) << r.err;
        EXPECT_EQ(r.errLines(), 1) << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    }
}
