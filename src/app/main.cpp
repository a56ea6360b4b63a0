/// \file main.cpp
/// \brief The `nori` command: load a scene, build its accelerator, render, write EXR + PNG.
#include "options.h"
#include "stats_json.h"
#include <nori/atomic_file.h>
#include <nori/renderer.h>
#include <nori/resolver.h>
#include <nori/scene.h>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <tbb/global_control.h>
#include <unistd.h>

using namespace nori;

namespace {

std::atomic<bool> g_cancel{false};

extern "C" void onInterrupt(int) {
    // Second Ctrl-C: the user really wants out.
    if (g_cancel.exchange(true)) std::_Exit(130);
}

/// Fail before the (possibly long) render if the output folder cannot take the images.
void checkOutputFolder(const std::string &base) {
    namespace fs = std::filesystem;
    fs::path folder = fs::path(base).parent_path();
    if (folder.empty()) folder = ".";
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) throw NoriException("{}: output folder does not exist", folder.string());
    if (access(folder.c_str(), W_OK) != 0)
        throw NoriException("{}: output folder is not writable: {}", folder.string(), std::strerror(errno));
}

int run(const CommandLine &cl) {
    for (const std::string &dir : cl.searchPath) fileResolver().append(dir);
    int threads = cl.threads > 0 ? cl.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    // Bounds every TBB algorithm: the accel build and the renderer alike.
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    checkOutputFolder(cl.outputBase);
    // A folder in the way of an image would only fail after the render, possibly after the
    // other image was already replaced: refuse before anything is written.
    for (const char *ext : {".exr", ".png"}) {
        std::error_code ec;
        if (std::filesystem::is_directory(cl.outputBase + ext, ec))
            throw NoriException("{}{}: is a folder, cannot write the image there", cl.outputBase, ext);
    }
    if (!cl.statsJsonPath.empty()) checkOutputFolder(cl.statsJsonPath);

    auto start = std::chrono::steady_clock::now();
    std::unique_ptr<Scene> scene = loadScene(cl.scenePath, cl.overrides);
    double totalMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const Accel &accel = scene->accel();
    double loadMs = totalMs - accel.buildMilliseconds();
    if (!cl.quiet)
        std::fprintf(stderr, "Loaded %u triangles in %.1f ms; built %s in %.1f ms\n", accel.triangleCount(), loadMs,
                     accel.toString().c_str(), accel.buildMilliseconds());
    if (cl.printStats)
        for (const AccelStat &stat : accel.statistics())
            std::fprintf(stderr, "  %-20s %s\n", stat.name.c_str(),
                         (stat.integral ? fmt::format("{}", (long long)stat.value) : fmt::format("{:.3f}", stat.value)).c_str());

    std::signal(SIGINT, onInterrupt);
    RenderSettings settings;
    settings.threads = threads;
    settings.progress = !cl.quiet;
    settings.cancel = &g_cancel;
    RenderResult result = BlockRenderer(*scene).render(settings);
    std::signal(SIGINT, SIG_DFL);

    if (!cl.quiet) {
        std::fprintf(stderr, "Rendered %dx%d at %d spp in %.1f ms: %llu rays, %.2f Mrays/s\n",
                     result.image.width(), result.image.height(), scene->sampler().sampleCount(), result.milliseconds,
                     (unsigned long long)result.rays, result.rays / (result.milliseconds * 1e3));
        if (result.droppedSamples)
            std::fprintf(stderr, "Warning: %llu samples were NaN or infinite and left out\n",
                         (unsigned long long)result.droppedSamples);
    }
    if (!result.complete) {
        std::string partial = cl.outputBase + "-partial.exr";
        result.image.saveEXR(partial);
        std::fprintf(stderr, "Interrupted after %d of %d blocks; partial image saved as %s\n", result.blocksRendered,
                     result.blockCount, partial.c_str());
        return 130;
    }
    result.image.saveEXR(cl.outputBase + ".exr");
    result.image.savePNG(cl.outputBase + ".png");
    if (!cl.statsJsonPath.empty())
        AtomicFile::write(cl.statsJsonPath, statsJson(RunFigures{cl.scenePath, threads, loadMs}, *scene, result));
    if (!cl.quiet) std::fprintf(stderr, "Wrote %s.exr and %s.png\n", cl.outputBase.c_str(), cl.outputBase.c_str());
    return 0;
}

} // namespace

int main(int argc, char **argv) {
    CliApp cli("nori", "Renders a Nori XML scene to an OpenEXR image (linear) and a PNG (sRGB) beside it.");
    CommandLine cl;
    cl.declare(cli);
    if (std::optional<int> status = cli.parse(argc, argv, [&] { cl.finish(cli); })) return *status;
    try {
        return run(cl);
    } catch (const NoriException &e) {
        std::fprintf(stderr, "nori: %s\n", e.what());
    } catch (const std::bad_alloc &) {
        std::fprintf(stderr, "nori: out of memory\n");
    } catch (const std::exception &e) {
        std::fprintf(stderr, "nori: internal error: %s\n", e.what());
    }
    return 1;
}
