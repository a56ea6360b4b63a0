/// \file test_cli_outputs.cpp
/// \brief Issue 11 through the real `nori`: outputs as one transaction (names checked first,
/// temporaries, renames under a folder lock, signals while writing) and hostile inputs that
/// must neither block nor grow without bound, each answered by one short line.
#include "run_tool.h"
#include <gtest/gtest.h>
#include <temp_dir.h>
#include <zlib.h>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sys/mount.h>
#include <sys/statvfs.h>
#include <thread>

using namespace nori;
namespace fs = std::filesystem;

namespace {

const std::string kNori = toolPath("nori");
const fs::path kCorpus = fs::path(NORI_SOURCE_DIR) / "tests" / "data" / "bad";

std::string readFile(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::set<std::string> listing(const fs::path &dir) {
    std::set<std::string> names;
    for (const auto &entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
    return names;
}

/// good.xml (16x16, one triangle) and its mesh in \p dir, optionally \p size pixels wide and high.
std::string writeScene(const fs::path &dir, const std::string &name = "scene.xml", int size = 16) {
    std::string xml = readFile(kCorpus / "good.xml");
    for (const char *key : {"\"width\" value=\"16\"", "\"height\" value=\"16\""}) {
        std::string k = key;
        xml.replace(xml.find(k), k.size(), k.substr(0, k.find('=') + 1) + "\"" + std::to_string(size) + "\"");
    }
    std::ofstream(dir / name, std::ios::binary) << xml;
    if (!fs::exists(dir / "tri.obj")) fs::copy_file(kCorpus / "tri.obj", dir / "tri.obj");
    return (dir / name).string();
}

/// Width of an EXR / PNG written by nori (from their headers).
int pngWidth(const std::string &bytes) {
    if (bytes.size() < 24) return -1;
    const unsigned char *p = reinterpret_cast<const unsigned char *>(bytes.data()) + 16;
    return p[0] << 24 | p[1] << 16 | p[2] << 8 | p[3];
}

void expectNoTemporaries(const fs::path &dir) {
    for (const std::string &name : listing(dir)) EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name;
}

/// A render to \p dir/out over earlier images, with the test hook raising \p signals while writing.
ToolRun renderWithSignals(const TempDir &dir, const std::string &signals, std::vector<std::string> extraArgs = {}) {
    std::string scene = writeScene(dir.path());
    dir.write("out.exr", "earlier exr");
    dir.write("out.png", "earlier png");
    ToolSetup hook;
    hook.env = {"NORI_TEST_SIGNALS_WHILE_WRITING=" + signals};
    std::vector<std::string> args = {"-q", "-o", dir.file("out")};
    args.insert(args.end(), extraArgs.begin(), extraArgs.end());
    args.push_back(scene);
    return runTool(kNori, args, hook);
}

} // namespace

TEST(CliOutputs, OutputNamesWithoutAFileNameAreRefusedBeforeAnyWork) {
    TempDir dir;
    std::string scene = writeScene(dir.path());
    fs::create_directory(dir.path() / "outdir");
    ToolSetup inDir;
    inDir.cwd = dir.path().string();
    for (const std::string &name : {std::string(""), std::string("outdir/"), std::string("/"), std::string(".exr"),
                                    std::string("outdir/.png")}) {
        SCOPED_TRACE("-o '" + name + "'");
        std::set<std::string> before = listing(dir.path());
        ToolRun r = runTool(kNori, {"-q", "-o", name, scene}, inDir);
        EXPECT_EQ(r.code, 2) << r.err;
        EXPECT_EQ(r.errLines(), 1) << r.err;
        EXPECT_NE(r.err.find("--output"), std::string::npos) << r.err;
        EXPECT_EQ(listing(dir.path()), before);
        EXPECT_TRUE(fs::is_empty(dir.path() / "outdir"));
    }
    EXPECT_FALSE(fs::exists("/.exr"));
}

TEST(CliOutputs, StatsJsonOnAFolderOrOnAnImageIsRefusedBeforeTheRender) {
    TempDir dir;
    std::string scene = writeScene(dir.path());
    dir.write("out.exr", "earlier exr");
    dir.write("out.png", "earlier png");
    fs::create_directory(dir.path() / "stats");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {dir.file("stats"), "is a folder"}, {dir.file("out.exr"), "given for two outputs at once"},
        {dir.file("./out.png"), "given for two outputs at once"}, {dir.file("out-partial.exr"), "two outputs"},
        {dir.file("out.png.tmp-1-0"), "named like the temporary file of the output"}};
    for (const auto &[stats, message] : cases) {
        SCOPED_TRACE(stats);
        ToolRun r = runTool(kNori, {"-q", "-o", dir.file("out"), "--stats-json", stats, scene});
        EXPECT_EQ(r.code, 1) << r.err;
        EXPECT_EQ(r.errLines(), 1) << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
        EXPECT_EQ(readFile(dir.path() / "out.exr"), "earlier exr");
        EXPECT_EQ(readFile(dir.path() / "out.png"), "earlier png");
    }
}

TEST(CliOutputs, MissingSceneInMissingFolderNamesTheScene) {
    ToolRun r = runTool(kNori, {"-q", "/nonexistent-folder/scene.xml"});
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "nori: /nonexistent-folder/scene.xml: cannot open: No such file or directory\n");
}

// /dev/zero never ends and /dev/stdin may be a pipe: refused before they are opened.
TEST(CliInputs, DeviceAsSceneIsRefusedAtOnce) {
    TempDir dir;
    ToolRun r = runTool(kNori, {"-q", "-o", dir.file("out"), "/dev/zero"});
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "nori: /dev/zero: cannot open: is a device, not a scene file\n");
}

// The hook raises the signals after the EXR went to its temporary file and before the PNG.
TEST(CliOutputs, OneSignalWhileWritingCompletesTheWrite) {
    for (const auto &[signals, status] : std::vector<std::pair<std::string, int>>{{"INT", 130}, {"TERM", 143}}) {
        SCOPED_TRACE(signals);
        TempDir dir;
        ToolRun r = renderWithSignals(dir, signals, {"--stats-json", dir.file("s.json")});
        EXPECT_TRUE(r.exited);
        EXPECT_EQ(r.code, status) << r.err;
        EXPECT_NE(r.err.find("the outputs were written completely"), std::string::npos) << r.err;
        EXPECT_EQ(pngWidth(readFile(dir.path() / "out.png")), 16);
        EXPECT_NE(readFile(dir.path() / "out.exr"), "earlier exr");
        EXPECT_TRUE(fs::exists(dir.path() / "s.json"));
        expectNoTemporaries(dir.path());
    }
}

TEST(CliOutputs, SecondSignalWhileWritingLeavesEarlierOutputsAndNoTemporary) {
    for (const std::string signals : {"INT,INT", "TERM,INT", "HUP,TERM"}) {
        SCOPED_TRACE(signals);
        TempDir dir;
        ToolRun r = renderWithSignals(dir, signals);
        EXPECT_TRUE(r.exited);
        EXPECT_GE(r.code, 129) << r.err;
        EXPECT_EQ(readFile(dir.path() / "out.exr"), "earlier exr");
        EXPECT_EQ(readFile(dir.path() / "out.png"), "earlier png");
        EXPECT_EQ(listing(dir.path()), (std::set<std::string>{"out.exr", "out.png", "scene.xml", "tri.obj"}));
    }
}

// Run A pauses between its two renames (folder locked); run B, 20x20 pixels, must wait for it.
// Without the lock B renames both of its images meanwhile and A's PNG lands after them.
TEST(CliOutputs, ConcurrentRendersToOneNameNeverMixThePair) {
    TempDir dir;
    std::string sceneA = writeScene(dir.path(), "a.xml", 16), sceneB = writeScene(dir.path(), "b.xml", 20);
    const std::string marker = dir.file("paused");
    ToolSetup pause;
    pause.env = {"NORI_TEST_PAUSE_AFTER_RENAME=" + marker};
    ToolRun a;
    std::thread runA([&] { a = runTool(kNori, {"-q", "-t", "1", "-o", dir.file("out"), sceneA}, pause); });
    for (int i = 0; i < 3000 && !fs::exists(marker); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(fs::exists(marker));
    ToolRun b;
    std::thread runB([&] { b = runTool(kNori, {"-q", "-t", "1", "-o", dir.file("out"), sceneB}); });
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // B renders 20x20 in milliseconds
    fs::remove(marker);
    runA.join();
    runB.join();
    EXPECT_EQ(a.code, 0) << a.err;
    EXPECT_EQ(b.code, 0) << b.err;
    // B came last: its pair, whole.
    EXPECT_EQ(pngWidth(readFile(dir.path() / "out.png")), 20);
    EXPECT_NE(readFile(dir.path() / "out.exr").find(std::string("\x13\x00\x00\x00", 4)), std::string::npos)
        << "the EXR's data window must end at x = 19";
    expectNoTemporaries(dir.path());
}

// A small tmpfs (root only): the EXR fits, the PNG does not. Nothing may be replaced.
TEST(CliOutputs, FullDiskReplacesNeitherImage) {
    TempDir dir;
    std::string scene = writeScene(dir.path(), "scene.xml", 128);
    ToolRun sizes = runTool(kNori, {"-q", "-o", dir.file("probe"), scene});
    ASSERT_EQ(sizes.code, 0) << sizes.err;
    const auto exrSize = fs::file_size(dir.path() / "probe.exr"), pngSize = fs::file_size(dir.path() / "probe.png");
    const fs::path disk = dir.path() / "disk";
    fs::create_directory(disk);
    if (::mount("tmpfs", disk.c_str(), "tmpfs", 0, "size=1m") != 0) GTEST_SKIP() << "cannot mount a tmpfs here";
    struct Unmount {
        fs::path p;
        ~Unmount() { ::umount2(p.c_str(), MNT_DETACH); }
    } unmount{disk};
    std::ofstream(disk / "out.exr") << "earlier exr";
    std::ofstream(disk / "out.png") << "earlier png";
    // Leave room for the EXR only (tmpfs counts whole 4 KiB pages): the PNG cannot be written.
    struct statvfs vfs {};
    ASSERT_EQ(statvfs(disk.c_str(), &vfs), 0);
    const uint64_t freeBytes = uint64_t(vfs.f_bavail) * vfs.f_frsize;
    const uint64_t keep = (exrSize + 4095) / 4096 * 4096;
    ASSERT_GT(freeBytes, keep + pngSize);
    std::ofstream(disk / "filler", std::ios::binary) << std::string(freeBytes - keep, 'f');
    ASSERT_EQ(fs::file_size(disk / "filler"), freeBytes - keep);
    ToolRun r = runTool(kNori, {"-q", "-o", (disk / "out").string(), scene});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_EQ(r.errLines(), 1) << r.err;
    EXPECT_NE(r.err.find("out.png: cannot write"), std::string::npos) << r.err;
    EXPECT_TRUE(readFile(disk / "out.exr") == "earlier exr") << "the EXR was replaced";
    EXPECT_TRUE(readFile(disk / "out.png") == "earlier png") << "the PNG was replaced";
    EXPECT_EQ(listing(disk), (std::set<std::string>{"filler", "out.exr", "out.png"}));
}

TEST(CliInputs, EchoedValuesAreShortAndOnOneLine) {
    TempDir dir;
    writeScene(dir.path());
    std::string xml = readFile(dir.path() / "scene.xml");
    const std::string huge(10 << 20, 'x');
    std::string bad = xml;
    bad.replace(bad.find("value=\"16\""), 10, "value=\"" + huge + "\"");
    dir.write("huge.xml", bad);
    ToolRun r = runTool(kNori, {"-q", dir.file("huge.xml")});
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.errLines(), 1);
    EXPECT_LT(r.err.size(), 200u) << r.err.substr(0, 300);
    EXPECT_NE(r.err.find("huge.xml:6:"), std::string::npos) << r.err.substr(0, 300);
    // A mesh file name of 10 MB, and a newline and an escape sequence in the scene's own name.
    bad = xml;
    bad.replace(bad.find("tri.obj"), 7, huge);
    dir.write("hugename.xml", bad);
    r = runTool(kNori, {"-q", dir.file("hugename.xml")});
    EXPECT_EQ(r.errLines(), 1);
    EXPECT_LT(r.err.size(), 400u) << r.err.substr(0, 500);
    r = runTool(kNori, {"-q", dir.file("no\nsuch\x1b[2J.xml")});
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.errLines(), 1) << r.err;
    EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
}

TEST(CliInputs, FarButValidCameraRenders) {
    TempDir dir;
    writeScene(dir.path());
    std::string xml = readFile(dir.path() / "scene.xml");
    xml.replace(xml.find("  </camera>"), 0,
                "    <transform name=\"toWorld\"><lookat origin=\"0,0,1e8\" target=\"0,0,0\"/></transform>\n");
    dir.write("far.xml", xml);
    ToolRun r = runTool(kNori, {"-q", dir.file("far.xml")});
    EXPECT_EQ(r.code, 0) << r.err;
}

// Gzip data that claims (trailer) or holds far more than memory allows: the loader grows its
// buffer as data arrives and names the file when it must stop (1 GiB of address space here).
TEST(CliInputs, HostileGzipMeshesNameTheFileAndStayBounded) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "needs an address-space limit, which sanitizers cannot run under";
#endif
    TempDir dir;
    writeScene(dir.path());
    std::string xml = readFile(dir.path() / "scene.xml");
    // One member of 1 MiB of spaces compresses to ~1 KiB; 3000 of them hold ~3 GiB.
    std::string member;
    {
        std::string spaces(1 << 20, ' ');
        uLongf size = compressBound(uLong(spaces.size())) + 64;
        z_stream zs{};
        deflateInit2(&zs, 9, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY);
        member.resize(size);
        zs.next_in = reinterpret_cast<Bytef *>(spaces.data());
        zs.avail_in = uInt(spaces.size());
        zs.next_out = reinterpret_cast<Bytef *>(member.data());
        zs.avail_out = uInt(member.size());
        ASSERT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
        member.resize(zs.total_out);
        deflateEnd(&zs);
    }
    std::string bomb;
    for (int i = 0; i < 3000; ++i) bomb += member;
    dir.write("bomb.obj", bomb);
    // A 3 MB file cut short whose trailer claims 3 GB.
    std::string truncated = bomb.substr(0, 3 << 20);
    truncated.replace(truncated.size() - 4, 4, std::string("\x00\x00\x00\xC0", 4));
    dir.write("truncated.obj", truncated);
    ToolSetup limited;
    limited.limitAddressSpace = true;
    for (const char *mesh : {"bomb.obj", "truncated.obj"}) {
        SCOPED_TRACE(mesh);
        std::string scene = xml;
        scene.replace(scene.find("tri.obj"), 7, mesh);
        dir.write("gz.xml", scene);
        ToolRun r = runTool(kNori, {"-q", "-t", "1", dir.file("gz.xml")}, limited);
        EXPECT_TRUE(r.exited);
        EXPECT_EQ(r.code, 1) << r.err;
        EXPECT_EQ(r.errLines(), 1) << r.err;
        EXPECT_NE(r.err.find(std::string(mesh) + ": "), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("nori: out of memory"), std::string::npos) << r.err;
    }
}
