/// \file markdown_writer.h
/// \brief The seed's Table 1 layout (per depth) with Embree's column, plus a table of every run.
#pragma once

#include "bench_results.h"
#include <string>
#include <vector>

namespace nori::bench {

class MarkdownWriter {
public:
    /// \brief One section per mesh: Table 1 per (overlap, leaf size), then all runs.
    /// \p command is quoted at the top when not empty.
    static std::string format(const std::vector<MeshResult> &results, const std::string &command);
    /// \brief format() written atomically to \p path.
    static void write(const std::string &path, const std::vector<MeshResult> &results, const std::string &command);
};

} // namespace nori::bench
