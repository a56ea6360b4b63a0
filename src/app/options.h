/// \file options.h
/// \brief Command-line options of the `nori` renderer.
#pragma once

#include <nori/parser.h>
#include <string>
#include <vector>

namespace nori {

/// \brief Everything the command line can say. parse() throws NoriException on bad usage.
struct CommandLine {
    std::string scenePath;
    std::string outputBase;        ///< output path without extension (empty: next to the scene)
    int threads = 0;               ///< 0: all cores
    bool quiet = false;
    bool printStats = false;
    bool help = false;
    std::string statsJsonPath;
    std::vector<std::string> searchPath;
    SceneOverrides overrides;

    /// \brief Parse argv (without the program name).
    static CommandLine parse(const std::vector<std::string> &args);
    /// \brief The --help text.
    static std::string usage();
};

} // namespace nori
