/// \file test_cli_bad_input.cpp
/// \brief Bad input through the real `nori` binary: every case of tests/data/bad/MANIFEST.tsv must
// fail cleanly (exit code != 0, no signal), print exactly one line naming the right file and
// line, create no output file, and leave an earlier image of the same name byte for byte.
#include "run_tool.h"
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <sys/stat.h>

namespace fs = std::filesystem;
using nori::runTool;
using nori::ToolRun;
using nori::ToolSetup;

namespace {

const fs::path BadDir = fs::path(NORI_SOURCE_DIR) / "tests" / "data" / "bad";
const fs::path NoriBinary = fs::path(NORI_BINARY_DIR) / "nori";

/// One row of MANIFEST.tsv.
struct BadCase {
    std::string scene;    ///< scene file given to nori (relative to the corpus folder)
    std::string file;     ///< file the message must name
    std::string line;     ///< line the message must name ("-": the message cannot have one)
    std::string snippet;  ///< part of the message
};

/// Short description in test output (instead of gtest's byte dump).
void PrintTo(const BadCase &c, std::ostream *os) { *os << c.scene; }

std::vector<BadCase> readManifest() {
    std::vector<BadCase> cases;
    std::ifstream in(BadDir / "MANIFEST.tsv");
    std::string row;
    while (std::getline(in, row)) {
        if (row.empty() || row[0] == '#') continue;
        std::vector<std::string> fields;
        std::stringstream ss(row);
        std::string field;
        while (std::getline(ss, field, '\t')) fields.push_back(field);
        if (fields.size() != 4) throw std::runtime_error("MANIFEST.tsv: bad row: " + row);
        cases.push_back({fields[0], fields[1], fields[2], fields[3]});
    }
    return cases;
}

std::string readFile(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeFile(const fs::path &path, const std::string &data) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << data;
}

std::set<std::string> listDirectory(const fs::path &dir) {
    std::set<std::string> names;
    for (const auto &entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
    return names;
}

/// Run nori with \p args in a bounded address space.
ToolRun runNori(const std::vector<std::string> &args) {
    ToolSetup setup;
    setup.limitAddressSpace = true;
    return runTool(NoriBinary.string(), args, setup);
}

/// Does \p message name "FILE:LINE" (FILE as a whole path component, LINE not followed by a digit)?
bool namesFileAndLine(const std::string &message, const std::string &file, const std::string &line) {
    const std::string needle = file + ":" + line;
    for (size_t pos = message.find(needle); pos != std::string::npos; pos = message.find(needle, pos + 1)) {
        bool startOk = pos == 0 || message[pos - 1] == '/' || message[pos - 1] == ' ' || message[pos - 1] == '(';
        size_t after = pos + needle.size();
        bool endOk = after == message.size() || !std::isdigit((unsigned char)message[after]);
        if (startOk && endOk) return true;
    }
    return false;
}

/// The corpus copied into a fresh temporary folder, with the cases git cannot hold
/// (folders standing where files should be).
class CorpusCopy {
public:
    CorpusCopy() {
        char pattern[] = "/tmp/nori-bad-XXXXXX";
        if (!mkdtemp(pattern)) throw std::runtime_error("mkdtemp failed");
        root = pattern;
        fs::copy(BadDir, root / "bad", fs::copy_options::recursive);
        fs::create_directory(root / "bad" / "folder_not_a_mesh.obj");
        fs::create_directory(root / "bad" / "scene_is_folder.xml");
        // FIFOs with no writer: opening one for reading would block forever.
        for (const char *fifo : {"fifo.obj", "scene_is_fifo.xml"})
            if (mkfifo((root / "bad" / fifo).c_str(), 0600) != 0) throw std::runtime_error("mkfifo failed");
    }
    ~CorpusCopy() {
        std::error_code ec;
        fs::remove_all(root, ec);
    }
    fs::path root;
};

CorpusCopy &corpus() {
    static CorpusCopy copy;
    return copy;
}

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, FailsCleanlyWithOneLocatedMessage) {
    const BadCase &c = GetParam();
    const fs::path scene = corpus().root / "bad" / c.scene;
    const fs::path work = corpus().root / ("out-" + c.scene);
    fs::create_directories(work);

    // An earlier image of the same name must survive byte for byte.
    const std::string oldExr = "earlier EXR bytes of " + c.scene, oldPng = "earlier PNG bytes";
    writeFile(work / "image.exr", oldExr);
    writeFile(work / "image.png", oldPng);
    const std::set<std::string> before = listDirectory(work);

    for (const char *output : {"image.exr", "fresh.exr"}) {
        SCOPED_TRACE(output);
        ToolRun r = runNori({"-q", "-t", "1", "-o", (work / output).string(), scene.string()});
        EXPECT_TRUE(r.exited) << "killed by signal " << r.code << "; stderr:\n" << r.err;
        EXPECT_NE(r.code, 0) << "stderr:\n" << r.err;
        EXPECT_EQ(r.out, "");
        // Exactly one line: a single newline, at the end.
        ASSERT_FALSE(r.err.empty());
        EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "stderr:\n" << r.err;
        if (c.line != "-") {
            EXPECT_TRUE(namesFileAndLine(r.err, c.file, c.line))
                << "expected " << c.file << ":" << c.line << " in: " << r.err;
        } else {
            EXPECT_NE(r.err.find(c.file), std::string::npos) << "expected " << c.file << " in: " << r.err;
        }
        EXPECT_NE(r.err.find(c.snippet), std::string::npos) << "expected '" << c.snippet << "' in: " << r.err;
        EXPECT_EQ(listDirectory(work), before) << "an output (or temporary) file was created";
        EXPECT_EQ(readFile(work / "image.exr"), oldExr);
        EXPECT_EQ(readFile(work / "image.png"), oldPng);
    }
}

std::string caseName(const ::testing::TestParamInfo<BadCase> &info) {
    std::string name = info.param.scene;
    for (char &ch : name)
        if (!std::isalnum((unsigned char)ch)) ch = '_';
    return name;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInput, ::testing::ValuesIn(readManifest()), caseName);

TEST(BadInputCorpus, IsLargeAndEveryFileIsListed) {
    std::vector<BadCase> cases = readManifest();
    EXPECT_GE(cases.size(), 30u);
    // Every scene in the folder is a case (except the positive control), so none is forgotten.
    std::set<std::string> listed;
    for (const BadCase &c : cases) listed.insert(c.scene);
    for (const auto &entry : fs::directory_iterator(BadDir)) {
        std::string name = entry.path().filename().string();
        if (entry.path().extension() == ".xml" && name != "good.xml") {
            EXPECT_TRUE(listed.count(name)) << name << " is not in MANIFEST.tsv";
        }
    }
}

// The positive control: the same harness sees a good scene succeed and overwrite the image,
// so the checks above can tell success from failure.
TEST(BadInputCorpus, GoodSceneRendersAndReplacesTheImage) {
    const fs::path work = corpus().root / "out-good";
    fs::create_directories(work);
    writeFile(work / "image.exr", "old");
    ToolRun r = runNori({"-q", "-t", "1", "-o", (work / "image.exr").string(),
                           (corpus().root / "bad" / "good.xml").string()});
    EXPECT_TRUE(r.exited);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(readFile(work / "image.exr"), "old");
    EXPECT_TRUE(fs::exists(work / "image.png"));
}

// Command-line mistakes give one line too, and never touch an image.
TEST(BadInputCorpus, BadCommandLinesFailWithOneLine) {
    const fs::path work = corpus().root / "out-cli";
    fs::create_directories(work);
    const std::string scene = (corpus().root / "bad" / "good.xml").string();
    const std::string out = (work / "x.exr").string();
    const std::vector<std::vector<std::string>> cases = {
        {"--spp", "0", "-o", out, scene},         {"-t", "-3", "-o", out, scene},
        {"--spp", "1e3", "-o", out, scene},       {"--accel", "nope", "-o", out, scene},
        {"--bogus", "-o", out, scene},            {"-o", out},
        {"-o", out, scene, scene},                {"-o", (work / "x.jpg").string(), scene},
        {"-o", (work / "no" / "such" / "x.exr").string(), scene}, {"-o", out, scene, "--spp"},
    };
    for (const auto &args : cases) {
        ToolRun r = runNori(args);
        EXPECT_TRUE(r.exited);
        EXPECT_NE(r.code, 0) << args[0];
        EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
        EXPECT_FALSE(fs::exists(work / "x.exr"));
        EXPECT_FALSE(fs::exists(work / "x.png"));
    }
    // A folder where one of the output images should go: a clean error, and the other image
    // (written first or second) is not replaced either.
    for (const char *folder : {"folder.exr", "folder.png"}) {
        fs::path dir = work / folder;
        fs::create_directories(dir);
        fs::path other = work / (std::string("folder") + (dir.extension() == ".exr" ? ".png" : ".exr"));
        writeFile(other, "earlier image");
        const std::set<std::string> before = listDirectory(work);
        ToolRun r = runNori({"-q", "-t", "1", "-o", (work / "folder").string(), scene});
        EXPECT_TRUE(r.exited);
        EXPECT_NE(r.code, 0);
        EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
        EXPECT_NE(r.err.find(folder), std::string::npos) << r.err;
        EXPECT_EQ(listDirectory(work), before);
        EXPECT_TRUE(fs::is_empty(dir));
        EXPECT_EQ(readFile(other), "earlier image") << folder;
        fs::remove_all(dir);
        fs::remove(other);
    }
}

} // namespace
