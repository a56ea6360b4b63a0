/// \file stats_json.cpp
/// \brief statsJson(): the run's figures and the accelerator's statistics through nlohmann::json.
#include "stats_json.h"
#include <nori/renderer.h>
#include <nori/scene.h>
#include <nlohmann/json.hpp>

namespace nori {

std::string statsJson(const RunFigures &run, const Scene &scene, const RenderResult &result) {
    const Accel &accel = scene.accel();
    nlohmann::ordered_json json;
    json["scene"] = run.scenePath;
    json["accel"] = accel.toString();
    json["threads"] = run.threads;
    json["width"] = scene.camera().outputSize().x();
    json["height"] = scene.camera().outputSize().y();
    json["spp"] = scene.sampler().sampleCount();
    json["load_ms"] = run.loadMs;
    json["render_ms"] = result.milliseconds;
    json["rays"] = result.rays;
    // Rays by kind: rays = rays_closest_hit + rays_shadow; camera rays are among the closest hits.
    json["rays_camera"] = result.cameraRays;
    json["rays_closest_hit"] = result.closestHitRays;
    json["rays_shadow"] = result.shadowRays;
    json["mrays_per_s"] = result.milliseconds > 0.0 ? result.rays / (result.milliseconds * 1e3) : 0.0;
    json["complete"] = result.complete;
    // Under mpirun: each rank's share of the blocks and rays (threads is per rank).
    if (!result.ranks.empty()) {
        json["processes"] = result.ranks.size();
        nlohmann::ordered_json ranks = nlohmann::ordered_json::array();
        for (const RankShare &share : result.ranks) {
            nlohmann::ordered_json entry;
            entry["blocks"] = share.blocks;
            entry["rays"] = share.closestHitRays + share.shadowRays;
            entry["rays_camera"] = share.cameraRays;
            entry["rays_closest_hit"] = share.closestHitRays;
            entry["rays_shadow"] = share.shadowRays;
            ranks.push_back(entry);
        }
        json["ranks"] = ranks;
    }
    // The accelerator's own statistics (build_ms, triangles, node counts, bytes, ...).
    for (const AccelStat &stat : accel.statistics()) {
        if (stat.integral) json[stat.name] = (long long)stat.value;
        else json[stat.name] = stat.value;
    }
    // A file name need not be UTF-8; replacing stray bytes keeps the document valid JSON.
    return json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

} // namespace nori
