#include <nori/object.h>
#include "options.h"
#include <charconv>
#include <filesystem>

namespace nori {

namespace {
int parsePositive(const std::string &option, const std::string &text, int maxValue) {
    int value = 0;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size() || value <= 0 || value > maxValue)
        throw NoriException("{}: expected an integer in [1, {}], got '{}'", option, maxValue, text);
    return value;
}

std::string joined(const std::vector<std::string> &names) {
    std::string s;
    for (const auto &n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}
} // namespace

std::string CommandLine::usage() {
    return fmt::format(
        "Usage: nori [options] SCENE.xml\n"
        "\n"
        "Renders a Nori XML scene to an OpenEXR image (linear) and a PNG (sRGB) beside it.\n"
        "\n"
        "Options:\n"
        "  -o, --output FILE     output image (FILE.exr and FILE.png; a .exr/.png suffix is optional).\n"
        "                        Default: the scene's name next to the scene file.\n"
        "  -t, --threads N       render (and build) with N threads; 1 runs a plain single-threaded\n"
        "                        loop. Default: all cores.\n"
        "  --spp N               samples per pixel (overrides the sampler's sampleCount)\n"
        "  --accel NAME          accelerator: {} (default: octree, or the scene's <accel>)\n"
        "  --max-depth N         octree: maximum subdivision depth (default 16, at most 32)\n"
        "  --leaf-size N         octree: nodes with fewer triangles become leaves (default 512)\n"
        "  --overlap MODE        octree: triangle/cell overlap test, exact (default) or bbox\n"
        "  --traversal NAME      octree: simd (default), sorted (both exact) or seed (inexact, for comparison)\n"
        "  --intersector NAME    ray/triangle test: watertight (default) or mt (Moller-Trumbore)\n"
        "  -a, --search-path DIR look for scene files in DIR too (repeatable; after the scene's folder)\n"
        "  --stats               print the accelerator's statistics\n"
        "  --stats-json FILE     write load/build/render times, rays and accel statistics as JSON\n"
        "  -q, --quiet           no progress display and no summary\n"
        "  -h, --help            show this help\n"
        "\n"
        "Ctrl-C stops after the blocks in flight and saves NAME-partial.exr.\n"
        "Scene types: integrators {}; samplers {}; filters {}; cameras {}; meshes {}; bsdfs {}.\n",
        joined(NoriObjectFactory::registeredNames(NoriObject::EAccel)),
        joined(NoriObjectFactory::registeredNames(NoriObject::EIntegrator)),
        joined(NoriObjectFactory::registeredNames(NoriObject::ESampler)),
        joined(NoriObjectFactory::registeredNames(NoriObject::EReconstructionFilter)),
        joined(NoriObjectFactory::registeredNames(NoriObject::ECamera)),
        joined(NoriObjectFactory::registeredNames(NoriObject::EMesh)),
        joined(NoriObjectFactory::registeredNames(NoriObject::EBSDF)));
}

CommandLine CommandLine::parse(const std::vector<std::string> &args) {
    CommandLine cl;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string &arg = args[i];
        auto value = [&]() -> const std::string & {
            if (i + 1 >= args.size()) throw NoriException("{}: missing value (see --help)", arg);
            return args[++i];
        };
        auto where = [&] { return "command line (" + arg + ")"; };
        if (arg == "-h" || arg == "--help") cl.help = true;
        else if (arg == "-q" || arg == "--quiet") cl.quiet = true;
        else if (arg == "--stats") cl.printStats = true;
        else if (arg == "--stats-json") cl.statsJsonPath = value();
        else if (arg == "-o" || arg == "--output") cl.outputBase = value();
        else if (arg == "-t" || arg == "--threads") cl.threads = parsePositive(arg, value(), 1024);
        else if (arg == "--spp") cl.overrides.sampleCount = parsePositive(arg, value(), 1 << 20);
        else if (arg == "--accel") cl.overrides.accelType = value();
        else if (arg == "-a" || arg == "--search-path") cl.searchPath.push_back(value());
        else if (arg == "--max-depth") cl.overrides.accelProps.setInteger("maxDepth", parsePositive(arg, value(), 1 << 20), where());
        else if (arg == "--leaf-size") cl.overrides.accelProps.setInteger("leafSize", parsePositive(arg, value(), 1 << 30), where());
        else if (arg == "--overlap") cl.overrides.accelProps.setString("overlap", value(), where());
        else if (arg == "--traversal") cl.overrides.accelProps.setString("traversal", value(), where());
        else if (arg == "--intersector") cl.overrides.accelProps.setString("intersector", value(), where());
        else if (!arg.empty() && arg[0] == '-' && arg != "-") throw NoriException("unknown option '{}' (see --help)", arg);
        else if (cl.scenePath.empty()) cl.scenePath = arg;
        else throw NoriException("more than one scene given ('{}' and '{}')", cl.scenePath, arg);
    }
    if (cl.help) return cl;
    if (cl.scenePath.empty()) throw NoriException("no scene file given (see --help)");
    if (cl.overrides.accelType.size() &&
        !NoriObjectFactory::isRegistered(NoriObject::EAccel, cl.overrides.accelType))
        throw NoriException("--accel: unknown accelerator '{}' (known: {})", cl.overrides.accelType,
                            joined(NoriObjectFactory::registeredNames(NoriObject::EAccel)));
    // Output name: strip a known image suffix; both images are always written.
    namespace fs = std::filesystem;
    if (cl.outputBase.empty()) {
        fs::path scene(cl.scenePath);
        cl.outputBase = (scene.parent_path() / scene.stem()).string();
    } else {
        fs::path out(cl.outputBase);
        std::string ext = out.extension().string();
        if (ext == ".exr" || ext == ".png") cl.outputBase = (out.parent_path() / out.stem()).string();
        else if (!ext.empty()) throw NoriException("--output: '{}' must end in .exr or .png", cl.outputBase);
    }
    return cl;
}

} // namespace nori
