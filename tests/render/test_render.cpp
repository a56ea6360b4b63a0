/// \file test_render.cpp
/// \brief Tests of the block renderer: bit-identical images for any thread count, and the bunny against an Embree reference.
#include <gtest/gtest.h>
#include <embree_oracle.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nori/parser.h>
#include <nori/renderer.h>
#include <nori/scene.h>
#include <sstream>
#include <tbb/global_control.h>
#include <temp_dir.h>

using namespace nori;

namespace {

const std::string kBunnyScene = std::string(NORI_SHARED_DIR) + "/nori-scenes/pa1/bunny.xml";

/// The `normals` integrator recomputed from Embree's hits: an independent reference.
class EmbreeNormalsIntegrator : public Integrator {
public:
    explicit EmbreeNormalsIntegrator(const PropertyList &) {}
    void preprocess(const Scene &scene) override {
        for (const auto &mesh : scene.meshes()) m_meshes.push_back(mesh.get());
        m_oracle = std::make_unique<EmbreeOracle>(m_meshes);
        for (const Mesh *m : m_meshes) m_offsets.push_back((m_offsets.empty() ? 0 : m_offsets.back()) + m->triangleCount());
    }
    Color3f Li(const Scene &, Sampler &, const Ray3f &ray) const override {
        Hit hit;
        if (!m_oracle->intersect(ray, hit)) return Color3f(0.0f);
        size_t m = 0;
        while (hit.prim >= m_offsets[m]) ++m;
        const Mesh *mesh = m_meshes[m];
        uint32_t f = hit.prim - (m ? m_offsets[m - 1] : 0);
        Normal3f n = mesh->geometricNormal(f);
        if (mesh->hasNormals()) {
            const auto &face = mesh->faces()[f];
            const auto &N = mesh->normals();
            n = ((1 - hit.u - hit.v) * N[face[0]] + hit.u * N[face[1]] + hit.v * N[face[2]]).normalized();
        }
        return n.cwiseAbs().array();
    }
    std::string toString() const override { return "EmbreeNormals[]"; }

private:
    std::vector<const Mesh *> m_meshes;
    std::vector<uint32_t> m_offsets;
    std::unique_ptr<EmbreeOracle> m_oracle;
};
NORI_REGISTER_CLASS(EmbreeNormalsIntegrator, "test_embree_normals", EIntegrator);

/// Every sample is NaN: the renderer must leave each one out and count it once.
class NanIntegrator : public Integrator {
public:
    explicit NanIntegrator(const PropertyList &) {}
    Color3f Li(const Scene &, Sampler &, const Ray3f &) const override { return Color3f(std::nanf("")); }
    std::string toString() const override { return "Nan[]"; }
};
NORI_REGISTER_CLASS(NanIntegrator, "test_nan", EIntegrator);

RenderResult renderFile(const std::string &path, int threads, const SceneOverrides &overrides = {}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    std::unique_ptr<Scene> scene = loadScene(path, overrides);
    RenderSettings settings;
    settings.threads = threads;
    settings.progress = false;
    return BlockRenderer(*scene).render(settings);
}

std::string readFile(const std::string &path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

TEST(Render, ImageIsBitIdenticalForOneAndTwoThreads) {
    if (!std::filesystem::exists(kBunnyScene)) GTEST_SKIP() << "needs " << kBunnyScene;
    TempDir dir;
    // The bunny with ambient occlusion: random numbers and secondary rays both matter.
    std::string xml = readFile(kBunnyScene);
    xml.replace(xml.find("<integrator type=\"normals\"/>"), 28, "<integrator type=\"ao\"/>");
    xml.replace(xml.find("bunny.obj"), 9, std::string(NORI_SHARED_DIR) + "/nori-scenes/pa1/bunny.obj");
    xml.replace(xml.find("value=\"768\""), 11, "value=\"200\"");
    xml.replace(xml.find("value=\"768\""), 11, "value=\"136\"");
    std::string path = dir.write("bunny-ao.xml", xml);
    SceneOverrides overrides;
    overrides.sampleCount = 4;
    RenderResult one = renderFile(path, 1, overrides);
    RenderResult two = renderFile(path, 2, overrides);
    ASSERT_TRUE(one.complete && two.complete);
    ASSERT_EQ(one.image.size(), two.image.size());
    EXPECT_EQ(one.rays, two.rays);
    size_t differing = 0;
    double sum = 0.0;
    for (size_t i = 0; i < one.image.pixels().size(); ++i) {
        differing += (one.image.pixels()[i] != two.image.pixels()[i]).any();
        sum += one.image.pixels()[i].sum();
    }
    EXPECT_EQ(differing, 0u);
    EXPECT_GT(sum, 100.0);  // the image is not black
}

TEST(Render, BunnyNormalsMatchEmbreeReference) {
    if (!std::filesystem::exists(kBunnyScene)) GTEST_SKIP() << "needs " << kBunnyScene;
    // The same scene, same samples, but every camera ray answered by Embree.
    TempDir dir;
    std::string xml = readFile(kBunnyScene);
    xml.replace(xml.find("<integrator type=\"normals\"/>"), 28, "<integrator type=\"test_embree_normals\"/>");
    xml.replace(xml.find("bunny.obj"), 9, std::string(NORI_SHARED_DIR) + "/nori-scenes/pa1/bunny.obj");
    std::string referencePath = dir.write("bunny-embree.xml", xml);
    RenderResult ours = renderFile(kBunnyScene, 2);
    RenderResult reference = renderFile(referencePath, 2);
    ASSERT_EQ(ours.image.size(), Vector2i(768, 768));
    ASSERT_EQ(ours.image.size(), reference.image.size());
    size_t background = 0, differing = 0;
    float maxDiff = 0.0f;
    for (size_t i = 0; i < ours.image.pixels().size(); ++i) {
        float diff = (ours.image.pixels()[i] - reference.image.pixels()[i]).abs().maxCoeff();
        maxDiff = std::max(maxDiff, diff);
        differing += diff > 1e-3f;
        background += reference.image.pixels()[i].isZero();
    }
    std::printf("bunny: %zu of %zu pixels differ from the Embree reference by > 1e-3 (max %g); %zu background\n",
                differing, ours.image.pixels().size(), maxDiff, background);
    // Both answer every ray; only a hit on a shared edge may pick the neighbouring triangle,
    // whose interpolated normal is the same there: differences must be rare and small.
    EXPECT_LE(differing, ours.image.pixels().size() / 10000);
    EXPECT_GT(background, 100000u);           // the bunny does not fill the frame
    EXPECT_LT(background, 768u * 768u - 100000u);  // and is there
}

TEST(Render, EveryNonFiniteSampleIsCountedOnce) {
    TempDir dir;
    dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    std::string path = dir.write("nan.xml", R"(<scene>
  <integrator type="test_nan"/>
  <sampler type="independent"><integer name="sampleCount" value="3"/></sampler>
  <camera type="perspective"><integer name="width" value="40"/><integer name="height" value="24"/></camera>
  <mesh type="obj"><string name="filename" value="tri.obj"/></mesh>
</scene>)");
    for (int threads : {1, 2}) {
        RenderResult r = renderFile(path, threads);
        ASSERT_TRUE(r.complete);
        EXPECT_EQ(r.droppedSamples, 40u * 24u * 3u) << threads << " thread(s)";
    }
}
