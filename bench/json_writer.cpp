/// \file json_writer.cpp
/// \brief The bench results as JSON through nlohmann::json (keys in a fixed order).
#include "json_writer.h"
#include <nori/atomic_file.h>
#include <nlohmann/json.hpp>
#include <cmath>

namespace nori::bench {

namespace {

using Json = nlohmann::ordered_json;

/// A measured figure; a value that is not finite (nothing measured) becomes null.
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json setJson(const SetTiming &s, bool withRatio) {
    Json j;
    j["rays"] = uint64_t(s.rays);
    j["ms"] = number(s.ms);
    j["mrays_s"] = number(s.mraysPerS);
    if (withRatio) {
        j["ratio_vs_embree"] = number(s.ratioVsEmbree);
        j["embree_ms"] = number(s.embreeMs);
    }
    if (s.hasAccuracy) {
        j["mismatches"] = s.accuracy.mismatches;
        j["hit_miss_mismatches"] = s.accuracy.hitMiss;
        j["max_rel_t_error"] = number(s.accuracy.maxRelTError);
        if (s.accuracy.refereed) {
            j["disputed"] = s.accuracy.disputed;
            j["exact_wrong"] = s.accuracy.exactWrong;
            j["embree_exact_wrong"] = s.accuracy.peerWrong;
            j["reference_exact_wrong"] = s.accuracy.referenceWrong;
        }
    }
    j["samples_ms"] = Json::array();
    for (double v : s.samples) j["samples_ms"].push_back(number(v));
    return j;
}

/// The three ray sets as members of \p j, keyed by their names.
void addSets(Json &j, const std::array<SetTiming, 3> &sets, bool withRatio) {
    for (const SetTiming &s : sets) j[s.name] = setJson(s, withRatio);
}

Json embreeJson(const EmbreeResult &e, bool robust) {
    Json j;
    j["build_ms"] = number(e.buildMs);
    j["bytes"] = e.bytes;
    j["robust"] = robust;
    addSets(j, e.sets, robust);
    return j;
}

Json runJson(const RunResult &r) {
    Json j;
    j["accel"] = r.accel;
    j["default"] = r.hasConfig && r.config.isDefault;
    if (r.hasConfig) {
        if (!r.config.buildRule.empty()) j["buildRule"] = r.config.buildRule;
        j["maxDepth"] = r.config.maxDepth;
        j["leafSize"] = r.config.leafSize;
        j["overlap"] = r.config.overlap;
        j["traversal"] = r.config.traversal;
        j["intersector"] = r.config.intersector;
        if (!r.config.properties.empty()) {  // --octree-set, as given
            Json props = Json::object();
            for (const auto &[name, value] : r.config.properties) props[name] = value;
            j["properties"] = props;
        }
    }
    j["build_ms"] = number(r.buildMs);
    for (const AccelStat &s : r.stats) {
        if (s.name == "build_ms") continue;
        j[s.name] = s.integral ? Json((long long)std::llround(s.value)) : number(s.value);
    }
    addSets(j, r.sets, true);
    return j;
}

Json meshJson(const MeshResult &m) {
    Json j;
    j["mesh"] = m.mesh;
    j["triangles"] = m.triangles;
    j["threads"] = m.threads;
    j["clock"] = m.clock;
    j["machine"] = {{"cpu", m.cpu}, {"cpu_avx512", m.cpuAvx512}, {"octree_lanes", m.octreeLanes}};
    j["load_ms"] = number(m.loadMs);
    j["rays"] = {{"camera", m.camera},       {"width", m.width},   {"height", m.height},
                 {"spp", m.spp},             {"repeats", m.repeats}, {"generation_ms", number(m.rayGenerationMs)},
                 {"t_tolerance", Accuracy::Tolerance}, {"reference", "embree_robust"}};
    j["notes"] = m.notes;
    j["embree"] = embreeJson(m.embree, false);
    j["embree_robust"] = embreeJson(m.embreeRobust, true);
    j["runs"] = Json::array();
    for (const RunResult &r : m.runs) j["runs"].push_back(runJson(r));
    return j;
}

} // namespace

std::string JsonWriter::format(const std::vector<MeshResult> &results) {
    Json j;
    if (results.size() == 1) {
        j = meshJson(results.front());
    } else {
        j = Json::array();
        for (const MeshResult &m : results) j.push_back(meshJson(m));
    }
    // A mesh's file name need not be UTF-8; replacing stray bytes keeps the document valid.
    return j.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

void JsonWriter::write(const std::string &path, const std::vector<MeshResult> &results) {
    AtomicFile::write(path, format(results));
}

} // namespace nori::bench
