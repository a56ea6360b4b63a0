/// \file json_writer.h
/// \brief Serialises results in the JSON shape of issue 4 (plus extra keys).
#pragma once

#include "bench_results.h"
#include <string>
#include <vector>

namespace nori::bench {

class JsonWriter {
public:
    /// \brief One object per mesh; a JSON array when there are several.
    static std::string format(const std::vector<MeshResult> &results);
    /// \brief format() written atomically to \p path.
    static void write(const std::string &path, const std::vector<MeshResult> &results);
};

} // namespace nori::bench
