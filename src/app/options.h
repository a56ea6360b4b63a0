/// \file options.h
/// \brief Command-line options of the `nori` renderer.
#pragma once

#include "cli_app.h"
#include <nori/parser.h>
#include <string>
#include <vector>

namespace nori {

/// \brief Everything the command line can say.
struct CommandLine {
    std::string scenePath;
    std::string outputBase;        ///< output path without extension (empty: next to the scene)
    int threads = 0;               ///< 0: all cores
    bool quiet = false;
    bool printStats = false;
    std::string statsJsonPath;
    std::vector<std::string> searchPath;
    SceneOverrides overrides;

    /// \brief Declare the options on \p cli; they fill this object while it parses.
    void declare(CliApp &cli);
    /// \brief After a successful parse: cross-option checks (UsageError) and derived values.
    void finish(const CliApp &cli);

private:
    int m_spp = 0;
};

} // namespace nori
