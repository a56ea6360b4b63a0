/// \file options.cpp
/// \brief The `nori` command line: declared on CLI11, checked across options, defaulted.
#include "options.h"
#include <nori/object.h>
#include <filesystem>
#include <fmt/ranges.h>

namespace nori {

namespace {

const char *const OutputGroup = "Output";
const char *const RenderGroup = "Rendering";
const char *const OctreeGroup = "Octree (only with --accel octree, the default)";

std::string names(NoriObject::EClassType type) {
    return fmt::format("{}", fmt::join(NoriObjectFactory::registeredNames(type), ", "));
}

} // namespace

void CommandLine::declare(CliApp &cli) {
    CLI::App &app = cli.app();
    // Like most tools: an option given twice takes its last value.
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("SCENE", scenePath, "the scene (Nori XML); put -- before a name that starts with '-'")
        ->required()
        ->option_text("SCENE.xml");

    app.add_option("-o,--output", outputBase,
                   "output name: writes FILE.exr (linear) and FILE.png (sRGB); a .exr/.png suffix is optional. "
                   "Default: the scene's name next to the scene")
        ->option_text("FILE")
        ->group(OutputGroup);
    app.add_flag("--stats", printStats, "print the accelerator's statistics")->group(OutputGroup);
    app.add_option("--stats-json", statsJsonPath,
                   "write load/build/render times, rays and the accelerator's statistics as JSON")
        ->option_text("FILE")
        ->group(OutputGroup);
    app.add_flag("-q,--quiet", quiet, "no progress display and no summary")->group(OutputGroup);

    app.add_option("-t,--threads", threads,
                   "threads for the build and the render; 1 runs a plain single-threaded loop. Default: all cores")
        ->check(integerIn(1, 1024))
        ->option_text("N")
        ->group(RenderGroup);
    app.add_option("--spp", m_spp, "samples per pixel (overrides the sampler's sampleCount)")
        ->check(integerIn(1, 1 << 20))
        ->option_text("N")
        ->group(RenderGroup);
    app.add_option("--accel", overrides.accelType,
                   fmt::format("accelerator: {} (default: the scene's <accel>, else octree)", names(NoriObject::EAccel)))
        ->check(oneOf(NoriObjectFactory::registeredNames(NoriObject::EAccel)))
        ->option_text("NAME")
        ->group(RenderGroup);
    app.add_option("-a,--search-path", searchPath,
                   "look for files named in the scene in DIR too (repeatable; after the scene's folder)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->allow_extra_args(false)
        ->option_text("DIR")
        ->group(RenderGroup);

    // The octree settings become properties of the scene's <accel>, as if written there.
    auto integerProperty = [this](const char *property) {
        return [this, property](int value) {
            overrides.accelProps.setInteger(property, value, fmt::format("command line ({})", property));
        };
    };
    auto stringProperty = [this](const char *property) {
        return [this, property](const std::string &value) {
            overrides.accelProps.setString(property, value, fmt::format("command line ({})", property));
        };
    };
    app.add_option_function<int>("--max-depth", integerProperty("maxDepth"),
                                 "deepest subdivision level (default 24; 16 with the count and seed build rules)")
        ->check(integerIn(0, 32))
        ->option_text("0..32")
        ->group(OctreeGroup);
    app.add_option_function<int>("--leaf-size", integerProperty("leafSize"),
                                 "a node with fewer triangles becomes a leaf (default 17; 512 with the count and seed build rules)")
        ->check(integerIn(1, 1 << 30))
        ->option_text("N")
        ->group(OctreeGroup);
    app.add_option_function<std::string>("--overlap", stringProperty("overlap"),
                                         "triangle/cell overlap test: exact (default) or bbox")
        ->option_text("MODE")
        ->group(OctreeGroup);
    app.add_option_function<std::string>("--traversal", stringProperty("traversal"),
                                         "simd (default), sorted (both exact) or seed (inexact, for comparison)")
        ->option_text("NAME")
        ->group(OctreeGroup);
    app.add_option_function<std::string>("--intersector", stringProperty("intersector"),
                                         "ray/triangle test: watertight (default) or mt (Moller-Trumbore)")
        ->option_text("NAME")
        ->group(OctreeGroup);

    app.footer(fmt::format("Ctrl-C stops after the blocks in flight and saves NAME-partial.exr.\n"
                           "Scene types: integrators {}; samplers {}; filters {}; cameras {}; meshes {}; bsdfs {}.",
                           names(NoriObject::EIntegrator), names(NoriObject::ESampler),
                           names(NoriObject::EReconstructionFilter), names(NoriObject::ECamera),
                           names(NoriObject::EMesh), names(NoriObject::EBSDF)));
}

void CommandLine::finish(const CliApp &cli) {
    const CLI::App &app = const_cast<CliApp &>(cli).app();
    // An octree setting given with another accelerator would be silently meaningless.
    if (!overrides.accelType.empty() && overrides.accelType != "octree")
        for (const char *option : {"--max-depth", "--leaf-size", "--overlap", "--traversal", "--intersector"})
            if (app.count(option) != 0)
                throw UsageError(fmt::format("{} applies only to --accel octree, not to --accel {}", option,
                                             overrides.accelType));
    overrides.sampleCount = m_spp;

    // Output name: strip a known image suffix; both images are always written. A name that
    // is given must name a file: '' (an unset variable), "dir/", "/" or ".exr" would write
    // hidden or misplaced files, or fall back to the default and overwrite earlier images.
    namespace fs = std::filesystem;
    if (app.count("--output") == 0) {
        fs::path scene(scenePath);
        outputBase = (scene.parent_path() / scene.stem()).string();
        return;
    }
    const std::string given = outputBase;
    if (given.empty()) throw UsageError("--output: the name is empty");
    if (given.back() == '/') throw UsageError(fmt::format("--output: '{}' is a folder name, not a file name", given));
    std::string name = fs::path(given).filename().string();
    for (const char *ext : {".exr", ".png"})
        if (name.size() >= 4 && name.compare(name.size() - 4, 4, ext) == 0) {
            name.resize(name.size() - 4);
            outputBase.resize(outputBase.size() - 4);
        }
    if (name.empty() || name == "." || name == "..")
        throw UsageError(fmt::format("--output: '{}' has no file name before the suffix", given));
    if (name.find('.') != std::string::npos && fs::path(name).has_extension())
        throw UsageError(fmt::format("--output: '{}' must end in .exr or .png, or have no suffix", given));
}

} // namespace nori
