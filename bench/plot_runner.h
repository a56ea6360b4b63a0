/// \file plot_runner.h
/// \brief Draws the charts by running bench/plot.py on a results JSON file.
#pragma once

#include <string>

namespace nori::bench {

class PlotRunner {
public:
    /// \brief The plot script next to the sources (NORI_BENCH_PLOT_SCRIPT at build time).
    static std::string scriptPath();
    /// \brief Run `python plot.py JSON --out DIR`; throws NoriException if it fails.
    static void run(const std::string &python, const std::string &jsonPath, const std::string &outDir);
};

} // namespace nori::bench
