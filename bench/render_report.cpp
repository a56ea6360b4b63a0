/// \file render_report.cpp
/// \brief Markdown and JSON for nori-bench's full-render mode.
#include "render_report.h"
#include <nlohmann/json.hpp>
#include <fmt/format.h>

namespace nori::bench {

namespace {

std::string baseName(const std::string &path) {
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

nlohmann::ordered_json runJson(const RenderRun &run) {
    return {{"accel", run.accel},
            {"build_ms", run.buildMs},
            {"render_ms", run.renderMs},
            {"samples_ms", run.samplesMs},
            {"rays", run.rays},
            {"mrays_s", run.renderMs > 0.0 ? double(run.rays) / run.renderMs / 1000.0 : 0.0}};
}

} // namespace

std::string RenderReport::header() {
    return "| scene | W×H×spp | threads | rays (octree / Embree) | octree ms | Embree ms | ×Embree | RMSE / mean | "
           "max abs / mean | pixels differing | > 1% of mean |\n"
           "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
}

std::string RenderReport::row(const RenderComparison &r) {
    const ImageDiff &d = r.diff;
    return fmt::format("| {} | {}×{}×{} | {} | {} / {} | {:.0f} | {:.0f} | {:.3f} | {:.2e} | {:.2e} | {:.4f}% | {:.4f}% |\n",
                       baseName(r.scene), r.width, r.height, r.spp, r.threads, r.octree.rays, r.embree.rays,
                       r.octree.renderMs, r.embree.renderMs, r.ratioVsEmbree, d.rmseRel(), d.maxAbsRel(),
                       100.0 * d.differingFraction(), 100.0 * d.visibleFraction());
}

std::string RenderReport::markdown(const RenderComparison &r, const std::string &command) {
    std::string s = fmt::format("Full render, octree vs Embree (`{}`), median of {} interleaved renders each; "
                                "×Embree = Embree ms / octree ms.\n\n",
                                command, r.repeats);
    s += header() + row(r);
    if (!r.repeatsIdentical) s += "\nWarning: a repeated render did not reproduce its first image.\n";
    return s;
}

std::string RenderReport::json(const RenderComparison &r, const std::string &command) {
    const ImageDiff &d = r.diff;
    nlohmann::ordered_json j = {
        {"command", command},
        {"scene", r.scene},
        {"integrator", r.integrator},
        {"width", r.width},
        {"height", r.height},
        {"spp", r.spp},
        {"threads", r.threads},
        {"repeats", r.repeats},
        {"load_ms", r.loadMs},
        {"octree", runJson(r.octree)},
        {"embree", runJson(r.embree)},
        {"ratio_vs_embree", r.ratioVsEmbree},
        {"repeats_identical", r.repeatsIdentical},
        {"image_diff",
         {{"reference", "octree"},
          {"pixels", d.pixels},
          {"mean_octree", d.meanRef},
          {"mean_embree", d.meanTest},
          {"rmse", d.rmse},
          {"rmse_rel", d.rmseRel()},
          {"max_abs", d.maxAbs},
          {"max_abs_rel", d.maxAbsRel()},
          {"differing_pixels", d.differingPixels},
          {"differing_fraction", d.differingFraction()},
          {"visible_pixels", d.visiblePixels},
          {"visible_fraction", d.visibleFraction()}}}};
    return j.dump(2) + "\n";
}

} // namespace nori::bench
