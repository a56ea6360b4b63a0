/// \file bench_main.cpp
/// \brief nori-bench: the seed's Table 1 for any mesh, side by side with Embree 3.
#include "bench_options.h"
#include "heap_policy.h"
#include "bench_runner.h"
#include "json_writer.h"
#include "markdown_writer.h"
#include "mesh_source.h"
#include "octree_catalog.h"
#include "plot_runner.h"
#include "render_compare.h"
#include "render_report.h"
#include <app/cli_app.h>
#include <nori/atomic_file.h>
#include <fmt/ranges.h>
#include <tbb/global_control.h>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

using namespace nori;
using namespace nori::bench;

namespace {

/// The command as the Markdown report quotes it (arguments with blanks or quotes in '').
std::string commandLine(int argc, char **argv) {
    std::vector<std::string> words{"nori-bench"};
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        words.push_back(a.find_first_of(" \t'\"") != std::string::npos ? "'" + a + "'" : a);
    }
    return fmt::format("{}", fmt::join(words, " "));
}

/// --render: the scene rendered with its octree and with Embree; times and image difference.
int runRender(const BenchOptions &options, const std::string &command) {
    RenderCompareSettings settings;
    settings.scene = options.scene;
    settings.spp = options.wasGiven("--spp") ? options.spp : 0;
    settings.threads = options.threads;
    settings.repeats = options.repeats;
    settings.embreeRobust = options.embreeRobust;
    settings.imagesDir = options.renderImages;
    RenderComparison result = RenderCompare::run(settings);
    if (!options.jsonPath.empty()) {
        AtomicFile::write(options.jsonPath, RenderReport::json(result, command));
        std::fprintf(stderr, "[nori-bench] wrote %s\n", options.jsonPath.c_str());
    }
    if (!options.markdownPath.empty()) {
        AtomicFile::write(options.markdownPath, RenderReport::markdown(result, command));
        std::fprintf(stderr, "[nori-bench] wrote %s\n", options.markdownPath.c_str());
    }
    if (options.jsonPath.empty() && options.markdownPath.empty())
        std::fputs(RenderReport::markdown(result, command).c_str(), stdout);
    return 0;
}

int runBench(const BenchOptions &options, const std::string &command) {
    std::unique_ptr<tbb::global_control> limit;
    if (options.threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      size_t(options.threads));
    std::string jsonPath = options.jsonPath;
    if (jsonPath.empty() && !options.plotsDir.empty()) jsonPath = options.plotsDir + "/bench.json";
    // The folders of the reports are made before the (long) measurement, so that it cannot fail after it.
    for (const std::string &path : {jsonPath, options.markdownPath}) {
        std::filesystem::path folder = std::filesystem::path(path).parent_path();
        std::error_code ec;
        if (!path.empty() && !folder.empty()) std::filesystem::create_directories(folder, ec);
        if (ec) throw NoriException("{}: cannot create the folder {}: {}", path, folder.string(), ec.message());
    }
    if (options.render) return runRender(options, command);

    OctreeCatalog catalog(options);
    if (!OctreeCatalog::available())
        std::fprintf(stderr, "[nori-bench] note: no 'octree' accel in this build; measuring brute force and Embree "
                             "only (octree options are ignored)\n");
    else
        std::fprintf(stderr, "[nori-bench] %zu octree configuration(s); traversals: %s\n", catalog.configs().size(),
                     fmt::format("{}", fmt::join(catalog.traversals(), ",")).c_str());

    for (const std::string &note : catalog.skipped()) std::fprintf(stderr, "[nori-bench] note: %s\n", note.c_str());
    BenchRunner runner(options, catalog);
    std::vector<MeshResult> results;
    if (!options.scene.empty()) {
        results.push_back(runner.run(MeshSource::loadScene(options.scene)));
    } else if (options.meshes.empty()) {
        results.push_back(runner.run(MeshSource::generated()));
    } else {
        for (const std::string &path : options.meshes) {
            std::fprintf(stderr, "[nori-bench] loading %s\n", path.c_str());
            results.push_back(runner.run(MeshSource::loadMesh(path)));  // one mesh in memory at a time
        }
    }

    if (!jsonPath.empty()) {
        JsonWriter::write(jsonPath, results);
        std::fprintf(stderr, "[nori-bench] wrote %s\n", jsonPath.c_str());
    }
    if (!options.markdownPath.empty()) {
        MarkdownWriter::write(options.markdownPath, results, command);
        std::fprintf(stderr, "[nori-bench] wrote %s\n", options.markdownPath.c_str());
    }
    if (!options.plotsDir.empty()) {
        PlotRunner::run(options.python, jsonPath, options.plotsDir);
        std::fprintf(stderr, "[nori-bench] charts in %s\n", options.plotsDir.c_str());
    }
    if (jsonPath.empty() && options.markdownPath.empty())
        std::fputs(MarkdownWriter::format(results, command).c_str(), stdout);
    return 0;
}

} // namespace

int main(int argc, char **argv) {
    keepFreedMemoryForReuse();
    CliApp cli("nori-bench", "nori-bench: the seed's Table 1 for any mesh, side by side with Embree 3.");
    BenchOptions options;
    OptionParser::declare(cli, options);
    if (std::optional<int> status = cli.parse(argc, argv, [&] { OptionParser::finish(cli, options); }))
        return *status;
    try {
        return runBench(options, commandLine(argc, argv));
    } catch (const std::invalid_argument &e) {  // an option value the octree rejects
        return cli.usageError(e.what());
    } catch (const std::exception &e) {
        std::fprintf(stderr, "nori-bench: error: %s\n", oneLine(e.what()).c_str());
        return 1;
    }
}
