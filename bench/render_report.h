/// \file render_report.h
/// \brief Markdown and JSON for nori-bench's full-render mode.
#pragma once

#include "render_compare.h"
#include <string>

namespace nori::bench {

class RenderReport {
public:
    /// \brief The Markdown table header (two lines) for rows of row().
    static std::string header();
    /// \brief One table row: scene, size, rays, both render times, ratio, image difference.
    static std::string row(const RenderComparison &r);
    /// \brief Command, header and row, as printed or written by --markdown.
    static std::string markdown(const RenderComparison &r, const std::string &command);
    /// \brief The comparison as a JSON object (pretty-printed).
    static std::string json(const RenderComparison &r, const std::string &command);
};

} // namespace nori::bench
