/// \file bench_options.cpp
/// \brief nori-bench's options on CLI11: lists, ranges, what goes together, the --quick defaults.
#include "bench_options.h"
#include <app/cli_app.h>
#include <nori/resolver.h>
#include <fmt/format.h>

namespace nori::bench {

namespace {

const char *const InputGroup = "Inputs";
const char *const ContenderGroup = "Contenders (octree: the cross product of these lists)";
const char *const MeasureGroup = "Measurement";
const char *const RenderGroup = "Full-render mode (with --scene)";
const char *const OutputGroup = "Output";

/// A comma-separated list option whose items \p item accepts, stored through \p store.
template <typename Store>
CLI::Option *addList(CLI::App &app, const std::string &name, const std::string &help, CLI::Validator item, Store store) {
    return app
        .add_option_function<std::string>(name, [store](const std::string &text) { store(splitList(text)); }, help)
        ->check(listOf(item))
        ->option_text("LIST");
}

std::vector<int> toInts(const std::vector<std::string> &items) {
    std::vector<int> values;
    for (const std::string &item : items) values.push_back(std::stoi(item));  // checked by integerIn
    return values;
}

} // namespace

void OptionParser::declare(CliApp &cli, BenchOptions &o) {
    CLI::App &app = cli.app();
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    CLI::Option *mesh = app.add_option("--mesh", o.meshes,
                                       "OBJ mesh (.obj or .obj.gz); repeat for a scaling series (one result per mesh)")
                            ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
                            ->allow_extra_args(false)
                            ->option_text("FILE")
                            ->group(InputGroup);
    CLI::Option *scene = app.add_option("--scene", o.scene, "a Nori scene: its meshes and its camera")
                             ->multi_option_policy(CLI::MultiOptionPolicy::Throw)
                             ->excludes(mesh)
                             ->option_text("SCENE.xml")
                             ->group(InputGroup);
    app.add_option("-a", o.searchPath, "look for files named in --scene in DIR too (repeatable, as for nori)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->allow_extra_args(false)
        ->needs(scene)
        ->option_text("DIR")
        ->group(InputGroup);
    // A scene's own camera decides its image size: refused there rather than silently ignored.
    app.add_option("--width", o.width, "camera rays of a --mesh: image width (default 512)")
        ->check(integerIn(1, 1 << 14))->excludes(scene)->option_text("W")->group(InputGroup);
    app.add_option("--height", o.height, "image height of a --mesh (default 512)")
        ->check(integerIn(1, 1 << 14))->excludes(scene)->option_text("H")->group(InputGroup);
    app.add_option("--spp", o.spp, "jittered rays per pixel (default 4)")
        ->check(integerIn(1, 1 << 12))->option_text("S")->group(InputGroup);

    CLI::Option *defaultOnly =
        app.add_flag("--default-only", o.defaultOnly, "only the octree with its own default settings")
            ->group(ContenderGroup);
    std::vector<CLI::Option *> lists = {
        addList(app, "--build-rules", "octree build rules: sah, count, seed (default: the octree's own)",
                oneOf({"sah", "count", "seed"}),
                [&o](const std::vector<std::string> &items) { o.buildRules = items; }),
        addList(app, "--depths", "octree maxDepth values (default 20,25,30)", integerIn(0, 64),
                [&o](const std::vector<std::string> &items) { o.depths = toInts(items); }),
        addList(app, "--leaf-sizes", "octree leafSize values (default 10)", integerIn(1, 1 << 20),
                [&o](const std::vector<std::string> &items) { o.leafSizes = toInts(items); }),
        addList(app, "--overlaps", "exact, bbox (default both)", oneOf({"exact", "bbox"}),
                [&o](const std::vector<std::string> &items) { o.overlaps = items; }),
        // Checked against the octree itself (OctreeCatalog): it knows its traversals.
        addList(app, "--traversals", "octree traversals (default: every traversal the octree offers)",
                CLI::Validator([](std::string &) { return std::string(); }, ""),
                [&o](const std::vector<std::string> &items) { o.traversals = items; }),
        addList(app, "--intersectors", "mt, watertight (default both)", oneOf({"mt", "watertight"}),
                [&o](const std::vector<std::string> &items) { o.intersectors = items; }),
    };
    for (CLI::Option *list : lists) {
        list->group(ContenderGroup);
        defaultOnly->excludes(list);
    }
    // Properties the lists above vary are refused here (each run sets them itself).
    app.add_option_function<std::vector<std::string>>(
           "--octree-set",
           [&o](const std::vector<std::string> &items) {
               for (const std::string &item : items) {
                   const size_t eq = item.find('=');
                   o.octreeProperties.emplace_back(item.substr(0, eq), item.substr(eq + 1));
               }
           },
           "one more octree property for every octree run, NAME=VALUE (repeatable; true/false, integers and "
           "numbers are typed as such): e.g. termination=false, fold=false")
        ->check(CLI::Validator(
            [](std::string &item) -> std::string {
                const size_t eq = item.find('=');
                if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
                    return "expected NAME=VALUE, got '" + item + "'";
                const std::string name = item.substr(0, eq);
                for (const char *listed : {"buildRule", "maxDepth", "leafSize", "overlap", "traversal", "intersector"})
                    if (name == listed)
                        return "'" + name + "' is set by the contender lists (--build-rules, --depths, --leaf-sizes, "
                                            "--overlaps, --traversals, --intersectors)";
                return std::string();
            },
            "NAME=VALUE"))
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->allow_extra_args(false)
        ->option_text("NAME=VALUE")
        ->group(ContenderGroup);
    CLI::Option *noBrute =
        app.add_flag("--no-brute", o.noBrute, "skip brute force (it always skips meshes above 100k triangles)")
            ->group(ContenderGroup);
    app.add_option_function<int>("--brute-rays", [&o](int n) { o.bruteRays = size_t(n); },
                                 "rays per set for brute force, a strided subset (default 4096)")
        ->check(integerIn(1, 1 << 30))
        ->excludes(noBrute)
        ->option_text("N")
        ->group(ContenderGroup);

    app.add_option("--threads", o.threads, "TBB and Embree worker threads (default: all cores); 1 = single-threaded")
        ->check(integerIn(1, 1024))->option_text("N")->group(MeasureGroup);
    app.add_option("--repeats", o.repeats, "timed runs per contender and ray set, median reported (default 3)")
        ->check(integerIn(1, 1000))->option_text("R")->group(MeasureGroup);
    app.add_flag("--cpu-time", o.cpuTime,
                 "time the builds and the ray sets by the thread's CPU time, not the wall clock (needs --threads "
                 "1): on a shared machine, time spent waiting for a core counts for neither side")
        ->group(MeasureGroup);
    app.add_flag("--quick", o.quick,
                 "tiny CI configuration (64x64x1 rays, 1 repeat, depths 6,10; a generated mesh when no --mesh is given)")
        ->group(MeasureGroup);

    CLI::Option *render =
        app.add_flag("--render", o.render,
                     "render the scene with its own accel (the octree) and with Embree, same samples: both render "
                     "times (median of --repeats, interleaved), their ratio and the image difference; --spp "
                     "overrides the scene's sample count")
            ->needs(scene)
            ->group(RenderGroup);
    app.add_option("--render-images", o.renderImages,
                   "write octree.exr/png, embree.exr/png and diff.png (|difference| x 10) there")
        ->needs(render)->option_text("DIR")->group(RenderGroup);
    app.add_flag("--embree-robust", o.embreeRobust, "Embree with RTC_SCENE_FLAG_ROBUST")
        ->needs(render)->group(RenderGroup);

    app.add_option("--json", o.jsonPath, "results as JSON (an array when several meshes are given)")
        ->option_text("FILE")->group(OutputGroup);
    app.add_option("--markdown", o.markdownPath, "Table 1 layout plus Embree and ratios")
        ->option_text("FILE")->group(OutputGroup);
    app.add_option("--dump-disputed", o.dumpDisputed,
                   "write every ray the exact referee decides for the octree runs (ray, the octree's, Embree "
                   "default's and robust's answers and verdicts, the triangles they name, as hex floats)")
        ->option_text("FILE")->group(OutputGroup);
    app.add_option("--dump-answers", o.dumpAnswers,
                   "write every ray of every set with the octree runs' answer (binary records of nine floats: "
                   "origin, direction, mint, maxt, answer) to compare two builds ray by ray")
        ->option_text("FILE")->group(OutputGroup);
    CLI::Option *plots = app.add_option("--plots", o.plotsDir, "PNG charts (runs bench/plot.py)")
                             ->option_text("DIR")->group(OutputGroup);
    app.add_option("--python", o.python, "interpreter for the charts (default /usr/bin/python3)")
        ->needs(plots)->option_text("EXE")->group(OutputGroup);
    render->excludes(plots);
    app.footer("Progress goes to stderr; a bad argument prints one line and exits with status 2.");
}

void OptionParser::finish(CliApp &cli, BenchOptions &o) {
    for (const CLI::Option *option : cli.app().get_options())
        if (option->count() > 0) o.given.insert(option->get_name());
    for (const std::string &dir : o.searchPath) nori::fileResolver().append(dir);  // like nori -a
    if (o.cpuTime && o.threads != 1) throw UsageError("--cpu-time needs --threads 1 (one thread's CPU time)");
    if (o.quick) {
        // A tiny configuration for CI; explicit options still win.
        if (!o.wasGiven("--width")) o.width = 64;
        if (!o.wasGiven("--height")) o.height = 64;
        if (!o.wasGiven("--spp")) o.spp = 1;
        if (!o.wasGiven("--repeats")) o.repeats = 1;
        if (!o.wasGiven("--depths")) o.depths = {6, 10};
        if (!o.wasGiven("--overlaps")) o.overlaps = {"exact", "bbox"};
        if (!o.wasGiven("--intersectors")) o.intersectors = {"mt", "watertight"};
        if (!o.wasGiven("--brute-rays")) o.bruteRays = 512;
    } else if (o.meshes.empty() && o.scene.empty()) {
        throw UsageError("nothing to measure: give --mesh FILE, --scene SCENE.xml or --quick");
    }
}

} // namespace nori::bench
