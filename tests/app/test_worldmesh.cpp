/// \file test_worldmesh.cpp
/// \brief nori-worldmesh: a mesh baked into world space reads back as the renderer placed it,
/// and as a stand-in for Nori's missing `ajax.obj` it renders Nori's own Ajax scene exactly as
/// the dragon scene renders; bad input gets one line and no output file.
#include "run_tool.h"
#include <gtest/gtest.h>
#include <nori/mesh.h>
#include <nori/objloader.h>
#include <nori/parser.h>
#include <nori/scene.h>
#include <temp_dir.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using nori::runTool;
using nori::TempDir;
using nori::ToolRun;

namespace {

const std::string kWorldMesh = std::string(NORI_BINARY_DIR) + "/nori-worldmesh";
const std::string kNori = std::string(NORI_BINARY_DIR) + "/nori";
const std::string kShared = NORI_SHARED_DIR;

std::string contents(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

TEST(WorldMesh, ReadsBackAsTheRendererPlacedIt) {
    TempDir dir;
    // A quad with normals and texture coordinates, turned, scaled and moved.
    dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 0.25\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                          "vn 0 0 1\nvn 0.1 0 1\nvn 0 0.2 1\nvn 0.3 0.3 1\nf 1/1/1 2/2/2 3/3/3\nf 1/1/1 3/3/3 4/4/4\n");
    const std::string scene = dir.write(
        "scene.xml", "<scene><integrator type=\"normals\"/>"
                     "<mesh type=\"obj\"><string name=\"filename\" value=\"quad.obj\"/><transform name=\"toWorld\">"
                     "<scale value=\"3, 0.5, 7\"/><rotate axis=\"1, 2, 0.5\" angle=\"33\"/>"
                     "<translate value=\"1000.125, -3, 0.1\"/></transform></mesh>"
                     "<camera type=\"perspective\"/></scene>");
    const ToolRun run = runTool(kWorldMesh, {scene, dir.file("baked.obj")});
    ASSERT_EQ(run.code, 0) << run.err;
    std::unique_ptr<nori::Scene> loaded = nori::loadScene(scene);
    const nori::Mesh &placed = *loaded->meshes().at(0);
    const nori::MeshData baked = nori::loadObjFile(dir.file("baked.obj"));
    ASSERT_EQ(baked.faces, placed.faces());
    ASSERT_EQ(baked.positions.size(), placed.positions().size());
    for (size_t i = 0; i < baked.positions.size(); ++i) {
        EXPECT_EQ(baked.positions[i], placed.positions()[i]) << i;  // bit for bit
        EXPECT_EQ(baked.uvs.at(i), placed.uvs()[i]) << i;
        EXPECT_LT((baked.normals.at(i) - placed.normals()[i]).norm(), 1e-6f) << i;
    }
}

TEST(WorldMesh, StandInRendersNorisAjaxSceneAsTheDragonScene) {
    const std::string dragonScene = std::string(NORI_SOURCE_DIR) + "/scenes/dragon-smooth.xml";
    const std::string ajaxScene = kShared + "/nori-scenes/pa5/ajax/ajax-smooth.xml";
    if (!fs::exists(kShared + "/meshes/dragon_vrip.obj.gz") || !fs::exists(ajaxScene))
        GTEST_SKIP() << "the dragon or Nori's pa5 Ajax scene is not under " << kShared;
    TempDir dir;
    const std::string ajaxFolder = kShared + "/nori-scenes/pa5/ajax", meshes = kShared + "/meshes";
    // (Into a folder that does not exist yet: the tool makes it.)
    const std::string standIn = dir.file("standin");
    ToolRun run = runTool(kWorldMesh, {dragonScene, standIn + "/ajax.obj", "-a", meshes, "-a", ajaxFolder});
    ASSERT_EQ(run.code, 0) << run.err;
    // Nori's file, unmodified, with the stand-in found through -a; the same image, byte for byte.
    run = runTool(kNori, {ajaxScene, "-a", standIn, "--spp", "1", "-q", "-o", dir.file("ajax")});
    ASSERT_EQ(run.code, 0) << run.err;
    run = runTool(kNori, {dragonScene, "-a", meshes, "-a", ajaxFolder, "--spp", "1", "-q", "-o", dir.file("dragon")});
    ASSERT_EQ(run.code, 0) << run.err;
    const std::string a = contents(dir.file("ajax.exr")), b = contents(dir.file("dragon.exr"));
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << "Nori's ajax-smooth.xml with the stand-in renders differently from dragon-smooth.xml";
}

TEST(WorldMesh, BadInputGetsOneLineAndNoFile) {
    TempDir dir;
    const std::string scene = dir.write("scene.xml", "<scene><integrator type=\"normals\"/>"
                                                     "<camera type=\"perspective\"/></scene>");
    dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string withMesh = dir.write("mesh.xml", "<scene><integrator type=\"normals\"/><mesh type=\"obj\">"
                                                       "<string name=\"filename\" value=\"tri.obj\"/></mesh>"
                                                       "<camera type=\"perspective\"/></scene>");
    const std::string out = dir.file("out.obj");
    struct Case {
        std::vector<std::string> args;
        int code;
        std::string message;
    };
    const Case cases[] = {
        {{}, 2, "required"},
        {{dir.file("missing.xml"), out}, 1, "missing.xml"},
        {{scene, out}, 1, "--mesh 0: the scene has 0 meshes"},
        {{scene, out, "--mesh", "-1"}, 2, "--mesh"},
        {{dir.write("broken.xml", "<scene><mesh type=\"obj\">"), out}, 1, "broken.xml"},
        {{withMesh, dir.write("blocker", "x") + "/sub/out.obj"}, 1, "cannot create folder"},
    };
    for (const Case &c : cases) {
        const ToolRun run = runTool(kWorldMesh, c.args);
        EXPECT_TRUE(run.exited);
        EXPECT_EQ(run.code, c.code) << run.err;
        EXPECT_EQ(run.errLines(), 1) << run.err;
        EXPECT_NE(run.err.find(c.message), std::string::npos) << run.err;
        EXPECT_FALSE(fs::exists(out));
    }
}

} // namespace
