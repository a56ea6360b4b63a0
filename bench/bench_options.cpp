#include "bench_options.h"
#include <nori/resolver.h>
#include <fmt/format.h>
#include <set>
#include <stdexcept>

namespace nori::bench {

namespace {

[[noreturn]] void bad(const std::string &message) { throw std::invalid_argument(message); }

int parseInt(const std::string &option, const std::string &text, int lo, int hi) {
    size_t used = 0;
    long value = 0;
    try {
        value = std::stol(text, &used);
    } catch (const std::exception &) {
        bad(fmt::format("{}: '{}' is not an integer", option, text));
    }
    if (used != text.size()) bad(fmt::format("{}: '{}' is not an integer", option, text));
    if (value < lo || value > hi) bad(fmt::format("{}: {} is outside [{}, {}]", option, value, lo, hi));
    return int(value);
}

std::vector<std::string> splitList(const std::string &option, const std::string &text) {
    std::vector<std::string> items;
    size_t start = 0;
    while (true) {
        size_t comma = text.find(',', start);
        std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (item.empty()) bad(fmt::format("{}: empty item in list '{}'", option, text));
        items.push_back(item);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    std::set<std::string> seen;
    for (const std::string &item : items)
        if (!seen.insert(item).second) bad(fmt::format("{}: '{}' listed twice", option, item));
    return items;
}

std::vector<int> parseIntList(const std::string &option, const std::string &text, int lo, int hi) {
    std::vector<int> values;
    for (const std::string &item : splitList(option, text)) values.push_back(parseInt(option, item, lo, hi));
    return values;
}

std::vector<std::string> parseChoiceList(const std::string &option, const std::string &text,
                                         const std::vector<std::string> &allowed) {
    std::vector<std::string> values = splitList(option, text);
    for (const std::string &v : values) {
        bool ok = false;
        for (const std::string &a : allowed) ok = ok || a == v;
        if (!ok) {
            std::string list;
            for (const std::string &a : allowed) list += (list.empty() ? "" : ", ") + a;
            bad(fmt::format("{}: unknown value '{}' (expected one of: {})", option, v, list));
        }
    }
    return values;
}

} // namespace

BenchOptions OptionParser::parse(int argc, char **argv) {
    BenchOptions o;
    std::set<std::string> &given = o.given;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) bad(fmt::format("{} needs a value", arg));
            return argv[++i];
        };
        if (arg == "--help" || arg == "-h") {
            o.help = true;
            return o;
        }
        given.insert(arg);
        if (arg == "--mesh") o.meshes.push_back(value());
        else if (arg == "--scene") {
            if (!o.scene.empty()) bad("--scene given twice");
            o.scene = value();
        }
        else if (arg == "--width") o.width = parseInt(arg, value(), 1, 1 << 14);
        else if (arg == "--height") o.height = parseInt(arg, value(), 1, 1 << 14);
        else if (arg == "--spp") o.spp = parseInt(arg, value(), 1, 1 << 12);
        else if (arg == "--depths") o.depths = parseIntList(arg, value(), 0, 64);
        else if (arg == "--leaf-sizes") o.leafSizes = parseIntList(arg, value(), 1, 1 << 20);
        else if (arg == "--overlaps") o.overlaps = parseChoiceList(arg, value(), {"exact", "bbox"});
        else if (arg == "--traversals") o.traversals = splitList(arg, value());  // checked against the octree
        else if (arg == "--intersectors") o.intersectors = parseChoiceList(arg, value(), {"mt", "watertight"});
        else if (arg == "--threads") o.threads = parseInt(arg, value(), 1, 1024);
        else if (arg == "--repeats") o.repeats = parseInt(arg, value(), 1, 1000);
        else if (arg == "--default-only") o.defaultOnly = true;
        else if (arg == "--quick") o.quick = true;
        else if (arg == "--no-brute") o.noBrute = true;
        else if (arg == "--brute-rays") o.bruteRays = size_t(parseInt(arg, value(), 1, 1 << 30));
        else if (arg == "--render") o.render = true;
        else if (arg == "--render-images") o.renderImages = value();
        else if (arg == "--embree-robust") o.embreeRobust = true;
        else if (arg == "--json") o.jsonPath = value();
        else if (arg == "--markdown") o.markdownPath = value();
        else if (arg == "--plots") o.plotsDir = value();
        else if (arg == "-a") nori::fileResolver().append(value());  // like nori -a: where scene files are found
        else if (arg == "--python") o.python = value();
        else bad(fmt::format("unknown argument '{}' (see --help)", arg));
    }

    if (!o.scene.empty() && !o.meshes.empty()) bad("give either --mesh or --scene, not both");
    if ((o.render || given.count("--render-images") || o.embreeRobust) && o.scene.empty())
        bad("--render, --render-images and --embree-robust need --scene");
    if ((given.count("--render-images") || o.embreeRobust) && !o.render)
        bad("--render-images and --embree-robust apply to --render only");
    if (o.quick) {
        // A tiny configuration for CI; explicit options still win.
        if (!given.count("--width")) o.width = 64;
        if (!given.count("--height")) o.height = 64;
        if (!given.count("--spp")) o.spp = 1;
        if (!given.count("--repeats")) o.repeats = 1;
        if (!given.count("--depths")) o.depths = {6, 10};
        if (!given.count("--overlaps")) o.overlaps = {"exact", "bbox"};
        if (!given.count("--intersectors")) o.intersectors = {"mt", "watertight"};
        if (!given.count("--brute-rays")) o.bruteRays = 512;
    } else if (o.meshes.empty() && o.scene.empty()) {
        bad("nothing to measure: give --mesh FILE, --scene SCENE.xml or --quick (see --help)");
    }
    return o;
}

std::string OptionParser::usage() {
    return R"(nori-bench: the seed's Table 1 for any mesh, side by side with Embree 3.

usage: nori-bench --mesh FILE [--mesh FILE ...] | --scene SCENE.xml | --quick
                  [--width W --height H --spp S] [--depths 20,25,30] [--leaf-sizes 10]
                  [--overlaps exact,bbox] [--traversals seed,sorted,...] [--intersectors mt,watertight]
                  [--threads N] [--repeats R] [--default-only] [--quick]
                  [--json FILE] [--markdown FILE] [--plots DIR] [-a DIR]

inputs
  --mesh FILE          OBJ mesh (.obj or .obj.gz); repeat for a scaling series (one result per mesh)
  --scene SCENE.xml    a Nori scene: its meshes and its camera
  --width/--height/--spp  camera rays: width x height pixels, spp jittered rays each (default 512x512x4)

contenders (octree: the cross product of these lists)
  --depths LIST        octree maxDepth values (default 20,25,30)
  --leaf-sizes LIST    octree leafSize values (default 10)
  --overlaps LIST      exact, bbox (default both)
  --traversals LIST    octree traversals (default: every traversal the octree offers)
  --intersectors LIST  mt, watertight (default both)
  --default-only       only the octree with its own default settings
  --no-brute           skip brute force (it always skips meshes above 100k triangles)
  --brute-rays N       rays per set for brute force, a strided subset (default 4096)

measurement
  --threads N          TBB and Embree worker threads (default: all cores); 1 = single-threaded
  --repeats R          timed runs per contender and ray set, median reported (default 3)
  --quick              tiny CI configuration (64x64x1 rays, 1 repeat, depths 6,10; a generated
                       mesh when no --mesh is given)

full-render mode (with --scene)
  --render             render the scene with its accel (the octree) and with Embree, same samples;
                       report both render times (median of --repeats, interleaved), their ratio
                       and the image difference (--spp overrides the scene's sample count)
  --render-images DIR  write octree.exr/png, embree.exr/png and diff.png (|difference| x 10) there
  --embree-robust      Embree with RTC_SCENE_FLAG_ROBUST in render mode

output
  --json FILE          results as JSON (an array when several meshes are given)
  --markdown FILE      Table 1 layout plus Embree and ratios
  --plots DIR          PNG charts (runs bench/plot.py with /usr/bin/python3)
  -a DIR               look for files named in --scene in DIR too (repeatable, as for nori)
  --python EXE         interpreter for the charts (default /usr/bin/python3)
  --help               this text

Progress goes to stderr; a bad argument prints one line and exits with status 2.
)";
}

} // namespace nori::bench
