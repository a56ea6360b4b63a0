/// \file markdown_writer.cpp
/// \brief The seed's Table 1 layout (per depth) with Embree's column, plus a table of every run (implementation).
#include "markdown_writer.h"
#include <nori/atomic_file.h>
#include <fmt/ranges.h>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

namespace nori::bench {

namespace {

std::string num(double v, int decimals) {
    if (!std::isfinite(v) || v < 0.0) return "–";
    return fmt::format("{:.{}f}", v, decimals);
}

std::string count(double v) { return v < 0.0 ? "–" : fmt::format("{}", (long long)std::llround(v)); }

/// Ratios span 1e-4 (brute force) to ~1: three significant digits.
std::string ratio(double v) {
    if (!std::isfinite(v) || v <= 0.0) return "–";
    return v >= 0.995 ? fmt::format("{:.2f}", v) : fmt::format("{:.3g}", v);
}

std::string mib(double bytes) { return bytes < 0.0 ? "–" : fmt::format("{:.1f}", bytes / (1024.0 * 1024.0)); }

std::string row(const std::vector<std::string> &cells) { return fmt::format("| {} |\n", fmt::join(cells, " | ")); }

std::string setCell(const SetTiming &s) {
    return fmt::format("{} ({}×) {}", num(s.mraysPerS, 3), ratio(s.ratioVsEmbree),
                       s.hasAccuracy ? fmt::format("[{}]", s.accuracy.mismatches) : std::string());
}

/// Table 1 for the octree runs with one build rule, overlap and leaf size.
std::string table1(const MeshResult &m, const std::string &rule, const std::string &overlap, int leafSize) {
    std::vector<const RunResult *> runs;
    std::set<int> depthSet;
    std::vector<std::string> variants;  // traversal/intersector, in run order
    for (const RunResult &r : m.runs) {
        if (r.accel != "octree" || !r.hasConfig || r.config.buildRule != rule || r.config.overlap != overlap ||
            r.config.leafSize != leafSize)
            continue;
        runs.push_back(&r);
        depthSet.insert(r.config.maxDepth);
        std::string v = r.config.traversal + " / " + r.config.intersector;
        if (std::find(variants.begin(), variants.end(), v) == variants.end()) variants.push_back(v);
    }
    if (runs.empty()) return "";
    std::vector<int> depths(depthSet.begin(), depthSet.end());
    auto find = [&](int depth, const std::string &variant) -> const RunResult * {
        for (const RunResult *r : runs)
            if (r->config.maxDepth == depth && r->config.traversal + " / " + r->config.intersector == variant) return r;
        return nullptr;
    };
    // Build statistics do not depend on the traversal: take them from the first variant that exists.
    auto buildRun = [&](int depth) -> const RunResult * {
        for (const std::string &v : variants)
            if (const RunResult *r = find(depth, v)) return r;
        return nullptr;
    };

    std::string s = fmt::format("### Table 1: {}overlap `{}`, leafSize {}\n\n",
                                rule.empty() ? "" : fmt::format("build rule `{}`, ", rule), overlap, leafSize);
    std::vector<std::string> header{"maxDepth"};
    for (int d : depths) header.push_back(fmt::format("{}", d));
    header.push_back("Embree");
    s += row(header);
    s += row(std::vector<std::string>(header.size(), "---:"));
    auto statRow = [&](const std::string &label, auto cell, const std::string &embree) {
        std::vector<std::string> cells{label};
        for (int d : depths) {
            const RunResult *r = buildRun(d);
            cells.push_back(r ? cell(*r) : "–");
        }
        cells.push_back(embree);
        s += row(cells);
    };
    statRow("build_time (ms)", [](const RunResult &r) { return num(r.buildMs, 1); }, num(m.embree.buildMs, 1));
    statRow("leaf_node", [](const RunResult &r) { return count(r.stat("leaf_nodes")); }, "–");
    statRow("internal_node", [](const RunResult &r) { return count(r.stat("internal_nodes")); }, "–");
    statRow("avg_triangle", [](const RunResult &r) { return num(r.stat("avg_tris_per_leaf"), 2); }, "–");
    statRow("memory (MiB)", [](const RunResult &r) { return mib(r.stat("bytes")); }, mib(double(m.embree.bytes)));
    for (const std::string &v : variants) {
        std::vector<std::string> cells{fmt::format("render time, {} (ms, ×Embree) [mismatches]", v)};
        for (int d : depths) {
            const RunResult *r = find(d, v);
            cells.push_back(r ? fmt::format("{} ({}×) [{}]", num(r->sets[0].ms, 1), ratio(r->sets[0].ratioVsEmbree),
                                            r->sets[0].accuracy.mismatches)
                              : "–");
        }
        cells.push_back(num(m.embree.sets[0].ms, 1));
        s += row(cells);
    }
    s += "\n";
    return s;
}

std::string allRuns(const MeshResult &m) {
    std::string s = "### All runs\n\nMrays/s (ratio vs Embree) [mismatches vs Embree robust]\n\n";
    s += row({"contender", "build ms", "MiB", "primary", "diffuse", "shadow"});
    s += row({"---", "---:", "---:", "---:", "---:", "---:"});
    s += row({"**Embree** (default flags)", num(m.embree.buildMs, 1), mib(double(m.embree.bytes)),
              setCell(m.embree.sets[0]), setCell(m.embree.sets[1]), setCell(m.embree.sets[2])});
    s += row({"Embree robust", num(m.embreeRobust.buildMs, 1), mib(double(m.embreeRobust.bytes)),
              setCell(m.embreeRobust.sets[0]), setCell(m.embreeRobust.sets[1]), setCell(m.embreeRobust.sets[2])});
    for (const RunResult &r : m.runs) {
        std::string name = r.hasConfig ? "octree " + r.config.label() : r.accel;
        if (r.hasConfig && r.config.isDefault) name = "**" + name + "** (default)";
        if (!r.hasConfig) name += fmt::format(" ({} rays/set)", r.sets[0].rays);
        s += row({name, num(r.buildMs, 1), mib(r.stat("bytes")), setCell(r.sets[0]), setCell(r.sets[1]),
                  setCell(r.sets[2])});
    }
    s += "\n";
    return s;
}

} // namespace

std::string MarkdownWriter::format(const std::vector<MeshResult> &results, const std::string &command) {
    std::string s = "# nori-bench results\n\n";
    if (!command.empty()) s += "```\n" + command + "\n```\n\n";
    for (const MeshResult &m : results) {
        s += fmt::format("## {}\n\n", m.mesh);
        s += fmt::format("{} triangles, loaded in {:.0f} ms; {} thread(s); rays from the {} camera, {}×{}×{} spp "
                         "(primary {}, diffuse {}, shadow {}); median of {} run(s), interleaved with Embree.\n\n",
                         m.triangles, m.loadMs, m.threads, m.camera, m.width, m.height, m.spp, m.embree.sets[0].rays,
                         m.embree.sets[1].rays, m.embree.sets[2].rays, m.repeats);
        for (const std::string &n : m.notes) s += "- Note: " + n + "\n";
        if (!m.notes.empty()) s += "\n";
        std::vector<std::tuple<std::string, std::string, int>> groups;
        for (const RunResult &r : m.runs) {
            if (r.accel != "octree" || !r.hasConfig) continue;
            std::tuple<std::string, std::string, int> g{r.config.buildRule, r.config.overlap, r.config.leafSize};
            if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
        }
        for (const auto &[rule, overlap, leaf] : groups) s += table1(m, rule, overlap, leaf);
        if (groups.empty()) s += "_No octree runs (the octree accel is not in this build)._\n\n";
        s += allRuns(m);
    }
    return s;
}

void MarkdownWriter::write(const std::string &path, const std::vector<MeshResult> &results,
                           const std::string &command) {
    AtomicFile::write(path, format(results, command));
}

} // namespace nori::bench
