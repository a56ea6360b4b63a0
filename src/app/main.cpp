/// \file main.cpp
/// \brief The `nori` command: load a scene, build its accelerator, render, write EXR + PNG.
#include "interrupts.h"
#include "options.h"
#include "process_group.h"
#include "stats_json.h"
#include <nori/atomic_file.h>
#include <nori/block.h>
#include <nori/output_set.h>
#include <nori/parser.h>
#include <nori/renderer.h>
#include <nori/resolver.h>
#include <nori/scene.h>
#include <nori/statistical_test.h>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <memory>
#include <optional>
#include <tbb/global_control.h>
#include <sys/stat.h>
#include <unistd.h>

using namespace nori;

namespace {

/// An error as one short line, whatever it echoes (file names from the scene, the scene's own
/// name): control characters become '?', and a very long message keeps its start (FILE:LINE)
/// and its end.
std::string messageLine(const std::string &message) {
    constexpr size_t Keep = 160;
    if (message.size() <= 2 * Keep) return shown(message, message.size());
    return shown(message, Keep) + shown(std::string_view(message).substr(message.size() - Keep), Keep);
}

/// What main() prints (after "nori: ") for an error.
std::string describe(std::exception_ptr error) {
    try {
        std::rethrow_exception(error);
    } catch (const NoriException &e) {
        return messageLine(e.what());
    } catch (const std::bad_alloc &) {
        return "out of memory";
    } catch (const std::exception &e) {
        return "internal error: " + messageLine(e.what());
    } catch (...) {
        return "internal error";
    }
}

/// Under mpirun every rank parses the same command line: only rank 0 prints what that gives
/// (usage errors, --help, --version); the other ranks' stdout and stderr go to /dev/null meanwhile.
class OnlyRankZeroPrints {
public:
    explicit OnlyRankZeroPrints(const ProcessGroup *group) {
        if (!group || group->rank() == 0) return;
        std::fflush(nullptr);
        const int null = ::open("/dev/null", O_WRONLY);
        for (int fd : {1, 2}) {
            m_saved[fd - 1] = ::dup(fd);
            ::dup2(null, fd);
        }
        ::close(null);
    }
    ~OnlyRankZeroPrints() {
        if (m_saved[0] < 0) return;
        std::fflush(nullptr);
        for (int fd : {1, 2}) {
            ::dup2(m_saved[fd - 1], fd);
            ::close(m_saved[fd - 1]);
        }
    }

private:
    int m_saved[2] = {-1, -1};
};

/// Every file this run may write; all are checked before the scene is loaded.
std::vector<std::string> outputPaths(const CommandLine &cl) {
    std::vector<std::string> paths = {cl.outputBase + ".exr", cl.outputBase + ".png", cl.outputBase + "-partial.exr"};
    if (!cl.statsJsonPath.empty()) paths.push_back(cl.statsJsonPath);
    return paths;
}

/// Test hook: NORI_TEST_SIGNALS_WHILE_WRITING=INT[,TERM...] raises those signals after the first
/// output was written to its temporary file, so that tests need no timing luck.
void testHookSignalsWhileWriting() {
    const char *list = std::getenv("NORI_TEST_SIGNALS_WHILE_WRITING");
    if (!list) return;
    std::string names = list;
    for (size_t start = 0; start < names.size();) {
        size_t comma = std::min(names.find(',', start), names.size());
        std::string name = names.substr(start, comma - start);
        std::raise(name == "TERM" ? SIGTERM : name == "HUP" ? SIGHUP : SIGINT);
        start = comma + 1;
    }
}

/// Test hook: NORI_TEST_PAUSE_AFTER_RENAME=FILE creates FILE after the first rename (the output
/// folders still locked) and waits up to 30 s until the test removes it.
void testHookPauseAfterRename(const std::string &) {
    static bool paused = false;
    const char *marker = std::getenv("NORI_TEST_PAUSE_AFTER_RENAME");
    if (!marker || paused) return;
    paused = true;
    AtomicFile::write(marker, "paused\n");
    for (int i = 0; i < 3000 && ::access(marker, F_OK) == 0; ++i) ::usleep(10000);
}

/// Rename the outputs; a signal now only records itself, so that no mixed set is left.
void commit(OutputSet &outputs) {
    Interrupts::setCommitting(true);
    try {
        outputs.commit(testHookPauseAfterRename);
    } catch (...) {
        Interrupts::setCommitting(false);
        throw;
    }
    Interrupts::setCommitting(false);
}

/// Run the statistical tests of a test file; the report goes to stdout.
bool runTests(const CommandLine &cl) {
    std::unique_ptr<NoriObject> root = loadFromXML(cl.scenePath, cl.overrides);
    const auto *test = dynamic_cast<const StatisticalTest *>(root.get());
    if (!test) throw NoriException("{}: <test> of an unknown kind", root->location());
    return test->run(stdout);
}

int run(const CommandLine &options, ProcessGroup *group) {
    // Under mpirun every rank loads the scene and renders; rank 0 alone prints, checks the
    // outputs and writes them (the others are quiet).
    const bool leader = !group || group->rank() == 0;
    CommandLine cl = options;
    if (!leader) {
        cl.quiet = true;
        cl.printStats = false;
    }
    for (const std::string &dir : cl.searchPath) fileResolver().append(dir);
    int threads = cl.threads > 0 ? cl.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    // Bounds every TBB algorithm: the accel build and the renderer alike.
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));

    // Everything a bad scene or option makes fail. Under mpirun each rank fails on its own; they
    // then agree, so that the message is printed once and no rank waits for the others forever.
    bool isTest = false;
    std::unique_ptr<Scene> scene;
    double loadMs = 0.0;
    std::optional<std::string> failure;
    try {
        // The scene first: a missing scene is the mistake to report, not its (missing) folder.
        struct stat sceneStat {};
        if (::stat(cl.scenePath.c_str(), &sceneStat) != 0)
            throw NoriException("{}: cannot open: {}", cl.scenePath, std::strerror(errno));
        // A file whose root is <test> (Nori's ttest / chi2test) runs its tests and writes no image.
        isTest = rootElementName(cl.scenePath) == "test";
        if (!isTest) {
            // Every output before the (possibly long) load and render: nothing is lost to a bad name.
            if (leader) OutputSet::check(outputPaths(cl));
            Interrupts::install();
            auto start = std::chrono::steady_clock::now();
            scene = loadScene(cl.scenePath, cl.overrides);
            double totalMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            loadMs = totalMs - scene->accel().buildMilliseconds();
        }
    } catch (...) {
        if (!group) throw;
        failure = describe(std::current_exception());
    }
    if (group) {
        ProcessGroup::Fingerprint fingerprint{};
        if (scene) {
            const Vector2i size = scene->camera().outputSize();
            fingerprint = {size.x(), size.y(), scene->sampler().sampleCount(), BlockGenerator(size, 32).blockCount()};
        }
        if (std::optional<std::string> message = group->agree(failure, fingerprint)) {
            if (leader) std::fprintf(stderr, "nori: %s\n", message->c_str());
            return 1;
        }
    }
    // The tests of a <test> file run on rank 0 only (each test's samples come from one seed).
    if (isTest) return leader ? (runTests(cl) ? 0 : 1) : 0;

    const Accel &accel = scene->accel();
    if (!cl.quiet)
        std::fprintf(stderr, "Loaded %u triangles in %.1f ms; built %s in %.1f ms\n", accel.triangleCount(), loadMs,
                     accel.toString().c_str(), accel.buildMilliseconds());
    if (cl.printStats)
        for (const AccelStat &stat : accel.statistics())
            std::fprintf(stderr, "  %-20s %s\n", stat.name.c_str(),
                         (stat.integral ? fmt::format("{}", (long long)stat.value) : fmt::format("{:.3f}", stat.value)).c_str());

    RenderSettings settings;
    settings.threads = threads;
    settings.progress = !cl.quiet;
    settings.cancel = &Interrupts::cancelled();
    std::unique_ptr<BlockExchange> exchange;
    if (group && group->size() > 1) exchange = group->exchange(threads, settings.cancel);
    settings.exchange = exchange.get();
    RenderResult result;
    try {
        result = BlockRenderer(*scene).render(settings);
    } catch (...) {
        // The other ranks would wait for this one's blocks: end them all.
        if (exchange) group->abort(describe(std::current_exception()));
        throw;
    }
    // The other ranks sent their blocks to rank 0; what is left to do is rank 0's.
    if (!leader) return Interrupts::signal() != 0 ? Interrupts::exitStatus() : 0;

    if (!cl.quiet) {
        std::fprintf(stderr, "Rendered %dx%d at %d spp in %.1f ms: %llu rays, %.2f Mrays/s\n",
                     result.image.width(), result.image.height(), scene->sampler().sampleCount(), result.milliseconds,
                     (unsigned long long)result.rays, result.rays / (result.milliseconds * 1e3));
        if (result.droppedSamples)
            std::fprintf(stderr, "Warning: %llu samples were NaN or infinite and left out\n",
                         (unsigned long long)result.droppedSamples);
    }
    if (cl.printStats)
        for (size_t rank = 0; rank < result.ranks.size(); ++rank) {
            const RankShare &share = result.ranks[rank];
            const uint64_t rays = share.closestHitRays + share.shadowRays;
            std::fprintf(stderr, "  rank %-3zu %6d blocks (%5.1f%%) %14llu rays (%5.1f%%)\n", rank, share.blocks,
                         100.0 * share.blocks / std::max(1, result.blockCount), (unsigned long long)rays,
                         100.0 * double(rays) / double(std::max<uint64_t>(1, result.rays)));
        }
    // From here on a signal no longer loses the render: the outputs are written completely.
    OutputSet outputs;
    if (!result.complete) {
        std::string partial = cl.outputBase + "-partial.exr";
        outputs.add(partial, result.image.encodeEXR(partial));
        commit(outputs);
        std::fprintf(stderr, "Interrupted after %d of %d blocks; partial image saved as %s\n", result.blocksRendered,
                     result.blockCount, partial.c_str());
        // No signal here: another rank had one (Ctrl-C reaches every rank as SIGTERM from mpirun).
        return Interrupts::signal() != 0 ? Interrupts::exitStatus() : 128 + SIGTERM;
    }
    const std::string exr = cl.outputBase + ".exr", png = cl.outputBase + ".png";
    outputs.add(exr, result.image.encodeEXR(exr));
    testHookSignalsWhileWriting();
    outputs.add(png, result.image.encodePNG(png));
    if (!cl.statsJsonPath.empty())
        outputs.add(cl.statsJsonPath, statsJson(RunFigures{cl.scenePath, threads, loadMs}, *scene, result));
    commit(outputs);
    if (!cl.quiet) std::fprintf(stderr, "Wrote %s and %s\n", exr.c_str(), png.c_str());
    if (Interrupts::signal() != 0) {
        std::fprintf(stderr, "Interrupted while writing; the outputs were written completely first\n");
        return Interrupts::exitStatus();
    }
    return 0;
}

} // namespace

int main(int argc, char **argv) {
    // Under an MPI launcher (mpirun) this process is one rank of several; alone otherwise.
    std::unique_ptr<ProcessGroup> group = ProcessGroup::join(argc, argv);
    CliApp cli("nori", "Renders a Nori XML scene to an OpenEXR image (linear) and a PNG (sRGB) beside it.");
    CommandLine cl;
    cl.declare(cli);
    std::optional<int> status;
    {
        OnlyRankZeroPrints quiet(group.get());
        status = cli.parse(argc, argv, [&] { cl.finish(cli); });
    }
    if (status) return *status;
    try {
        return run(cl, group.get());
    } catch (...) {
        std::fprintf(stderr, "nori: %s\n", describe(std::current_exception()).c_str());
    }
    return 1;
}
