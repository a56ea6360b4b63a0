/// \file render_compare.cpp
/// \brief Full renders with the octree and with Embree, timed alternately, and their difference.
#include "render_compare.h"
#include <nori/parser.h>
#include <nori/renderer.h>
#include <nori/scene.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>

namespace nori::bench {

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

/// One loaded scene and the image of its first render.
struct Contender {
    std::unique_ptr<Scene> scene;
    RenderRun run;
    Bitmap first;
    bool identical = true;
};

bool samePixels(const Bitmap &a, const Bitmap &b) {
    return a.size() == b.size() && std::equal(a.pixels().begin(), a.pixels().end(), b.pixels().begin(),
                                              [](const Color3f &x, const Color3f &y) { return (x == y).all(); });
}

void renderOnce(Contender &c, int threads) {
    RenderSettings settings;
    settings.threads = threads;
    settings.progress = false;
    RenderResult r = BlockRenderer(*c.scene).render(settings);
    if (!r.complete) throw NoriException("{}: the render did not complete", c.run.accel);
    c.run.samplesMs.push_back(r.milliseconds);
    if (c.run.samplesMs.size() == 1) {
        c.first = std::move(r.image);
        c.run.rays = r.rays;
    } else {
        // The renderer seeds each block by its index: a repeat must give the same image.
        c.identical = c.identical && r.rays == c.run.rays && samePixels(r.image, c.first);
    }
}

void saveImages(const std::string &dir, const Contender &octree, const Contender &embree) {
    std::filesystem::create_directories(dir);
    octree.first.saveEXR(dir + "/octree.exr");
    octree.first.savePNG(dir + "/octree.png");
    embree.first.saveEXR(dir + "/embree.exr");
    embree.first.savePNG(dir + "/embree.png");
    // Differences amplified 10x, so that single pixels stand out.
    ImageDiff::absDifference(octree.first, embree.first, 10.0f).savePNG(dir + "/diff.png");
}

} // namespace

RenderComparison RenderCompare::run(const RenderCompareSettings &s) {
    RenderComparison result;
    result.scene = s.scene;
    result.repeats = s.repeats;
    result.threads = s.threads > 0 ? s.threads : int(std::max(1u, std::thread::hardware_concurrency()));

    SceneOverrides mine;
    mine.sampleCount = s.spp;
    SceneOverrides theirs = mine;
    theirs.accelType = "embree";
    theirs.accelProps.setBoolean("robust", s.embreeRobust, "nori-bench");
    theirs.accelProps.setInteger("threads", result.threads, "nori-bench");

    Contender octree, embree;
    auto start = std::chrono::steady_clock::now();
    octree.scene = loadScene(s.scene, mine);
    double totalMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    result.loadMs = totalMs - octree.scene->accel().buildMilliseconds();
    embree.scene = loadScene(s.scene, theirs);
    octree.run.accel = octree.scene->accel().toString();
    embree.run.accel = embree.scene->accel().toString();
    octree.run.buildMs = octree.scene->accel().buildMilliseconds();
    embree.run.buildMs = embree.scene->accel().buildMilliseconds();

    const Scene &scene = *octree.scene;
    result.integrator = scene.integrator().toString();
    result.width = scene.camera().outputSize().x();
    result.height = scene.camera().outputSize().y();
    result.spp = scene.sampler().sampleCount();

    // Embree first, then the octree, in every round: slow drift of a shared machine hits both.
    for (int i = 0; i < s.repeats; ++i) {
        renderOnce(embree, s.threads);
        renderOnce(octree, s.threads);
        std::fprintf(stderr, "[nori-bench] render %d/%d: embree %.1f ms, octree %.1f ms\n", i + 1, s.repeats,
                     embree.run.samplesMs.back(), octree.run.samplesMs.back());
    }
    octree.run.renderMs = median(octree.run.samplesMs);
    embree.run.renderMs = median(embree.run.samplesMs);
    result.ratioVsEmbree = octree.run.renderMs > 0.0 ? embree.run.renderMs / octree.run.renderMs : 0.0;
    result.diff = ImageDiff::compute(octree.first, embree.first);
    result.repeatsIdentical = octree.identical && embree.identical;
    if (!s.imagesDir.empty()) saveImages(s.imagesDir, octree, embree);
    result.octree = std::move(octree.run);
    result.embree = std::move(embree.run);
    return result;
}

} // namespace nori::bench
