/// \file test_ray_counts.cpp
/// \brief Rays by kind (camera, closest-hit, shadow) in the render result and in `nori --stats-json`,
/// on scenes where the exact counts are known: a camera inside a closed box sees a wall with every
/// ray, so `normals` traces one closest hit per sample, `simple` (light inside) one shadow ray more,
/// and `ao` one shadow ray per AO sample.
#include <gtest/gtest.h>
#include "../app/run_tool.h"
#include "scene_kit.h"
#include <nlohmann/json.hpp>
#include <nori/renderer.h>

using namespace nori;

namespace {

std::string boxScene(const TempDir &dir, const std::string &integrator) {
    dir.write("box.obj", kit::quadsObj(kit::cubeInward(Point3f(0, 0, 0), -1.0f, 1.0f)));
    return "<scene>\n  " + integrator +
           "\n  <sampler type=\"independent\"><integer name=\"sampleCount\" value=\"3\"/></sampler>\n"
           "  <camera type=\"perspective\"><integer name=\"width\" value=\"40\"/><integer name=\"height\" value=\"30\"/>\n"
           "    <float name=\"fov\" value=\"60\"/></camera>\n"
           "  <mesh type=\"obj\"><string name=\"filename\" value=\"box.obj\"/></mesh>\n</scene>\n";
}

RenderResult renderText(const TempDir &dir, const std::string &xml) {
    auto scene = kit::loadSceneText(dir, "box.xml", xml);
    RenderSettings settings;
    settings.threads = 1;
    settings.progress = false;
    return BlockRenderer(*scene).render(settings);
}

const uint64_t Samples = 40 * 30 * 3;

TEST(RayCounts, ExactOnAClosedBox) {
    TempDir dir;
    RenderResult normals = renderText(dir, boxScene(dir, "<integrator type=\"normals\"/>"));
    EXPECT_EQ(normals.cameraRays, Samples);
    EXPECT_EQ(normals.closestHitRays, Samples);
    EXPECT_EQ(normals.shadowRays, 0u);
    EXPECT_EQ(normals.rays, Samples);

    RenderResult simple = renderText(dir, boxScene(dir, "<integrator type=\"simple\"><point name=\"position\" value=\"0, 0.5, 0.2\"/>"
                                                        "<color name=\"energy\" value=\"1, 1, 1\"/></integrator>"));
    EXPECT_EQ(simple.cameraRays, Samples);
    EXPECT_EQ(simple.closestHitRays, Samples);
    EXPECT_EQ(simple.shadowRays, Samples);
    EXPECT_EQ(simple.rays, 2 * Samples);

    RenderResult ao = renderText(dir, boxScene(dir, "<integrator type=\"ao\"><integer name=\"samples\" value=\"5\"/></integrator>"));
    EXPECT_EQ(ao.closestHitRays, Samples);
    EXPECT_EQ(ao.shadowRays, 5 * Samples);
    EXPECT_EQ(ao.rays, 6 * Samples);
}

TEST(RayCounts, StatsJsonHasRaysByKind) {
    const std::string nori = toolPath("nori");
    if (!std::filesystem::exists(nori)) GTEST_SKIP() << "nori is not built";
    TempDir dir;
    std::string scene = dir.write("box.xml", boxScene(dir, "<integrator type=\"ao\"><integer name=\"samples\" value=\"2\"/></integrator>"));
    ToolRun r = runTool(nori, {"-q", "--stats-json", dir.file("stats.json"), "-o", dir.file("out"), scene});
    ASSERT_EQ(r.code, 0) << r.err;
    std::ifstream in(dir.file("stats.json"));
    nlohmann::json json = nlohmann::json::parse(in);
    EXPECT_EQ(json["rays_camera"].get<uint64_t>(), Samples);
    EXPECT_EQ(json["rays_closest_hit"].get<uint64_t>(), Samples);
    EXPECT_EQ(json["rays_shadow"].get<uint64_t>(), 2 * Samples);
    EXPECT_EQ(json["rays"].get<uint64_t>(), 3 * Samples);
}

} // namespace
