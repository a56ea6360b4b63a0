/// \file test_genscene.cpp
/// \brief nori-genscene: what it writes loads back bit for bit and renders as a Nori scene;
/// bad arguments give one line and no output files.
#include <gtest/gtest.h>
#include <nori/objloader.h>
#include <nori/parser.h>
#include <nori/scene.h>
#include <scene_generator.h>
#include <temp_dir.h>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

using namespace nori;

namespace {

const std::string kTool = std::string(NORI_BINARY_DIR) + "/scenes/generators/nori-genscene";

struct ToolRun {
    int status;
    std::string err;
};

/// Runs the tool with \p args (shell words), capturing stderr.
ToolRun genscene(const TempDir &dir, const std::string &args) {
    std::string errFile = dir.file("stderr.txt");
    int raw = std::system((kTool + " " + args + " 2>" + errFile + " >/dev/null").c_str());
    std::ifstream in(errFile);
    std::stringstream ss;
    ss << in.rdbuf();
    std::filesystem::remove(errFile);
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, ss.str()};
}

size_t lines(const std::string &text) { return size_t(std::count(text.begin(), text.end(), '\n')); }

TEST(Genscene, WritesWhatTheGeneratorMakes) {
    TempDir dir;
    ToolRun r = genscene(dir, "tabletop " + dir.path().string() + "/out --triangles 3000 --seed 5 --spp 2");
    ASSERT_EQ(r.status, 0) << r.err;
    gen::GeneratedScene expected = gen::generateScene("tabletop", gen::GenParams{3000, 5});

    MeshData loaded = loadObjFile(dir.file("out/tabletop.obj"));
    ASSERT_EQ(loaded.positions.size(), expected.mesh.positions.size());
    for (size_t i = 0; i < loaded.positions.size(); ++i) ASSERT_EQ(loaded.positions[i], expected.mesh.positions[i]) << i;
    EXPECT_EQ(loaded.faces, expected.mesh.faces);

    // The XML is a scene `nori` renders: it parses, and its camera is the generator's.
    auto scene = loadScene(dir.file("out/tabletop.xml"));
    ASSERT_EQ(scene->meshes().size(), 1u);
    EXPECT_EQ(scene->meshes()[0]->triangleCount(), expected.triangleCount());
    auto camera = gen::makeCamera(expected.camera);
    EXPECT_EQ(scene->camera().outputSize(), camera->outputSize());
    for (Point2f pixel : {Point2f(0.5f, 0.5f), Point2f(300.25f, 200.75f)}) {
        Ray3f a, b;
        scene->camera().sampleRay(a, pixel, Point2f(0.5f, 0.5f));
        camera->sampleRay(b, pixel, Point2f(0.5f, 0.5f));
        EXPECT_LT((a.o - b.o).norm(), 1e-5f);
        EXPECT_LT((a.d.normalized() - b.d.normalized()).norm(), 1e-5f);
    }
    // No temporary files are left behind.
    size_t files = 0;
    for (const auto &entry : std::filesystem::directory_iterator(dir.file("out"))) files += entry.is_regular_file();
    EXPECT_EQ(files, 2u);
}

// --rotate and --offset place the scene as GenParams::placement does, and the scene's comment
// says how, so that the written files can be made again.
TEST(Genscene, PlacesTheSceneAndSaysHow) {
    TempDir dir;
    ToolRun r = genscene(dir, "room " + dir.path().string() +
                                  "/out --triangles 6000 --seed 4 --rotate 1,2,0.5,33 --offset 3000,1000,-2000");
    ASSERT_EQ(r.status, 0) << r.err;
    gen::GenParams params{6000, 4};
    params.placement = {Vector3f(1.0f, 2.0f, 0.5f), 33.0f, Vector3f(3000.0f, 1000.0f, -2000.0f)};
    gen::GeneratedScene expected = gen::generateScene("room", params);
    MeshData loaded = loadObjFile(dir.file("out/room.obj"));
    ASSERT_EQ(loaded.positions.size(), expected.mesh.positions.size());
    for (size_t i = 0; i < loaded.positions.size(); ++i) ASSERT_EQ(loaded.positions[i], expected.mesh.positions[i]) << i;
    std::ifstream xml(dir.file("out/room.xml"));
    std::stringstream text;
    text << xml.rdbuf();
    EXPECT_NE(text.str().find("--seed 4 --rotate 1,2,0.5,33 --offset 3000,1000,-2000"), std::string::npos) << text.str();
}

TEST(Genscene, BadArgumentsGiveOneLineAndNoFiles) {
    TempDir dir;
    std::string out = dir.path().string() + "/out";
    struct Case {
        std::string args, message;
        int status;
    };
    const Case cases[] = {
        {"castle " + out, "unknown shape 'castle'", 2},
        {"room " + out + " --triangles 10", "needs between", 1},
        {"city " + out + " --triangles abc", "--triangles", 2},
        {"city " + out + " --triangles -5", "--triangles", 2},
        {"city " + out + " --triangles 0", "--triangles", 2},
        {"city " + out + " --integrator path", "--integrator", 2},
        {"city", "give SHAPE and OUT_DIR", 2},
        {"city " + out + " --rotate 1,2", "--rotate", 2},
        {"city " + out + " --offset 1,x,3", "--offset", 2},
        {"city " + out + " --rotate 0,0,0,30", "a rotation needs a finite nonzero axis", 1},
        {"city " + out + " --offset 1,inf,3", "an offset needs finite coordinates", 1},
    };
    for (const Case &c : cases) {
        ToolRun r = genscene(dir, c.args);
        EXPECT_EQ(r.status, c.status) << c.args << ": " << r.err;
        EXPECT_EQ(lines(r.err), 1u) << c.args << ": " << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
    }
    // An output folder that cannot be created (a file is in the way).
    std::string blocker = dir.write("blocker", "x");
    ToolRun r = genscene(dir, "coplanar " + blocker + "/sub");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("cannot create folder"), std::string::npos) << r.err;
}

} // namespace
