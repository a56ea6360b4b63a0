/// \file test_objloader_files.cpp
/// \brief Tests for loadObjFile: plain and gzip files, I/O and decompression errors, and the real
/// meshes in NORI_SHARED_DIR (skipped when that folder is missing).
#include <gtest/gtest.h>
#include <error_of.h>
#include <temp_dir.h>
#include <nori/objloader.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <zlib.h>

using namespace nori;
namespace fs = std::filesystem;

namespace {

using Tri = std::array<uint32_t, 3>;

void writeFile(const std::string &path, const std::string &bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    ASSERT_TRUE(out.good());
}

void writeGzip(const std::string &path, const std::string &text) {
    gzFile gz = gzopen(path.c_str(), "wb9");
    ASSERT_NE(gz, nullptr);
    ASSERT_EQ(gzwrite(gz, text.data(), unsigned(text.size())), int(text.size()));
    ASSERT_EQ(gzclose(gz), Z_OK);
}

std::string readBytes(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

const char *Square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                     "vn 0 0 1\nvn 0 0 -1\n";

} // namespace

// ---- files and gzip -------------------------------------------------------------------

TEST(ObjLoaderFile, PlainAndGzipFilesGiveTheSameMesh) {
    TempDir dir;
    std::string text = std::string(Square) + "# comment\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";
    for (int i = 0; i < 2000; ++i) text += "v 0.125 0.25 0.5\n"; // several inflate rounds
    writeFile(dir.file("a.obj"), text);
    writeGzip(dir.file("a.obj.gz"), text);
    writeGzip(dir.file("no_suffix.obj"), text); // detection is by magic bytes, not by name
    MeshData plain = loadObjFile(dir.file("a.obj"));
    for (const char *name : {"a.obj.gz", "no_suffix.obj"}) {
        MeshData gz = loadObjFile(dir.file(name));
        EXPECT_EQ(gz.positions, plain.positions) << name;
        EXPECT_EQ(gz.uvs, plain.uvs) << name;
        EXPECT_EQ(gz.normals, plain.normals) << name;
        EXPECT_EQ(gz.faces, plain.faces) << name;
    }
    EXPECT_EQ(plain.faces.size(), 2u);
    EXPECT_EQ(plain.positions.size(), 4u);
}

TEST(ObjLoaderFile, ConcatenatedGzipMembers) {
    TempDir dir;
    writeGzip(dir.file("1.gz"), "v 0 0 0\nv 1 0 0\n");
    writeGzip(dir.file("2.gz"), "v 0 1 0\nf 1 2 3\n");
    writeFile(dir.file("both.obj.gz"), readBytes(dir.file("1.gz")) + readBytes(dir.file("2.gz")));
    MeshData m = loadObjFile(dir.file("both.obj.gz"));
    EXPECT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.faces.size(), 1u);
}

TEST(ObjLoaderFile, MissingFile) {
    TempDir dir;
    std::string path = dir.file("nothing-here.obj");
    std::string msg = errorOf([&] { loadObjFile(path); });
    EXPECT_EQ(msg, path + ": cannot open: No such file or directory");
}

TEST(ObjLoaderFile, UnreadableFile) {
    if (geteuid() == 0) GTEST_SKIP() << "root can read files without read permission";
    TempDir dir;
    std::string path = dir.file("secret.obj");
    writeFile(path, "v 0 0 0\n");
    fs::permissions(path, fs::perms::none);
    std::string msg = errorOf([&] { loadObjFile(path); });
    EXPECT_EQ(msg, path + ": cannot open: Permission denied");
}

TEST(ObjLoaderFile, DirectoryInsteadOfFile) {
    TempDir dir;
    std::string path = dir.file("sub.obj");
    fs::create_directory(path);
    std::string msg = errorOf([&] { loadObjFile(path); });
    EXPECT_EQ(msg, path + ": cannot open: Is a directory, not a mesh file");
}

TEST(ObjLoaderFile, CorruptGzip) {
    TempDir dir;
    std::string text;
    for (int i = 0; i < 500; ++i) text += fmt::format("v {} {} {}\n", i, i * 0.5, -i);
    writeGzip(dir.file("good.gz"), text);
    std::string good = readBytes(dir.file("good.gz"));
    ASSERT_GT(good.size(), 100u);

    std::string flipped = good;
    for (size_t i = 20; i < 60; ++i) flipped[i] = char(~flipped[i]);
    std::string badCrc = good;
    badCrc[badCrc.size() - 6] = char(~badCrc[badCrc.size() - 6]);
    const std::pair<const char *, std::string> cases[] = {
        {"flipped.obj.gz", flipped},
        {"truncated.obj.gz", good.substr(0, good.size() / 2)},
        {"header-only.obj.gz", good.substr(0, 2)},
        {"bad-crc.obj.gz", badCrc},
        {"trailing.obj.gz", good + "junk"},
    };
    for (const auto &[name, bytes] : cases) {
        std::string path = dir.file(name);
        writeFile(path, bytes);
        std::string msg = errorOf([&] { loadObjFile(path); });
        EXPECT_EQ(msg.rfind(path + ": corrupt gzip data", 0), 0u) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

TEST(ObjLoaderFile, ErrorsInsideGzipReportFileAndLine) {
    TempDir dir;
    std::string path = dir.file("bad.obj.gz");
    writeGzip(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 7\n");
    EXPECT_EQ(errorOf([&] { loadObjFile(path); }).rfind(path + ":5: ", 0), 0u);
}

// ---- real meshes (counts from meshes/SOURCES.md) --------------------------------------

namespace {
std::string sharedMesh(const char *name) { return std::string(NORI_SHARED_DIR) + "/meshes/" + name; }
} // namespace

TEST(ObjLoaderShared, StanfordBunny) {
    std::string path = sharedMesh("stanford-bunny.obj");
    if (!fs::exists(path)) GTEST_SKIP() << path << " not found";
    MeshData m = loadObjFile(path);
    EXPECT_EQ(m.faces.size(), 69451u);
    EXPECT_EQ(m.positions.size(), 35947u); // includes its 1113 unreferenced vertices
    EXPECT_TRUE(m.uvs.empty());
    EXPECT_TRUE(m.normals.empty());
}

TEST(ObjLoaderShared, BeastQuadsAndTexCoords) {
    std::string path = sharedMesh("beast.obj");
    if (!fs::exists(path)) GTEST_SKIP() << path << " not found";
    MeshData m = loadObjFile(path);
    EXPECT_EQ(m.faces.size(), 64618u);
    EXPECT_TRUE(m.normals.empty());
    EXPECT_EQ(m.uvs.size(), m.positions.size());
    // 33963 distinct "v/vt" face tokens (counted with awk), i.e. more than its 32311 positions.
    EXPECT_EQ(m.positions.size(), 33963u);
    // First face "f 1/1 2/2 3/3 4/4": first vertex of the file with the first uv.
    EXPECT_EQ(m.faces[0], (Tri{0, 1, 2}));
    EXPECT_EQ(m.faces[1], (Tri{0, 2, 3}));
    EXPECT_EQ(m.positions[0], Point3f(0.000069f, 195.938904f, 37.986382f));
    EXPECT_EQ(m.uvs[0], Point2f(1.895248f, 0.902657f));
}

TEST(ObjLoaderShared, DragonGzip) {
    std::string path = sharedMesh("dragon_vrip.obj.gz");
    if (!fs::exists(path)) GTEST_SKIP() << path << " not found";
    MeshData m = loadObjFile(path);
    EXPECT_EQ(m.faces.size(), 871414u);
    EXPECT_EQ(m.positions.size(), 437645u);
    BoundingBox3f box;
    for (const Point3f &p : m.positions) box.expandBy(p);
    EXPECT_FLOAT_EQ(box.min.x(), -0.108324f);
    EXPECT_FLOAT_EQ(box.max.y(), 0.197173f);
}
