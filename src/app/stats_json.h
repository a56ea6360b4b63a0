/// \file stats_json.h
/// \brief The `--stats-json` document of one render.
#pragma once

#include <string>

namespace nori {

class Scene;
struct RenderResult;

/// \brief What one run of `nori` measured, beside the scene and the render result.
struct RunFigures {
    std::string scenePath;
    int threads = 0;
    double loadMs = 0.0;
};

/// \brief The statistics as a JSON object (keys in a fixed order, numbers that round-trip,
/// any file name correctly escaped; bytes that are not UTF-8 become U+FFFD).
std::string statsJson(const RunFigures &run, const Scene &scene, const RenderResult &result);

} // namespace nori
