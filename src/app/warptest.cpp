/// \file warptest.cpp
/// \brief `nori-warptest WARP [PARAM...]`: chi^2 test of a warping function against its pdf.
/// Exit status 0 when the test passes, 1 when it fails, 2 for a usage error.
#include "cli_app.h"
#include "validation/warp_catalog.h"
#include <cstdio>
#include <fmt/ranges.h>
#include <tbb/global_control.h>
#include <thread>

using namespace nori;

int main(int argc, char **argv) {
    std::string warpName, pdfName;
    std::vector<float> parameters, pdfParameters;
    float angle = 0.0f;
    int samplesPerCell = 1000, threads = 0;
    NamedWarp sampled, reference;

    CliApp cli("nori-warptest", fmt::format("chi^2 test of a warping function's samples against its pdf (exit 0 "
                                            "when it passes, 1 when it fails).\nWarps: {}; beckmann takes ALPHA, "
                                            "microfacet_brdf ALPHA [KD], the others no parameter.",
                                            fmt::join(warpNames(), ", ")));
    CLI::App &app = cli.app();
    app.add_option("WARP", warpName, "the warping function")->required();
    app.add_option("PARAM", parameters, "its parameters");
    app.add_option("--angle", angle, "incident angle of microfacet_brdf, degrees (default 0)")
        ->check(CLI::Range(-90.0f, 90.0f));
    app.add_option("--pdf", pdfName, "expected counts from this warp's pdf instead (a test that must fail)");
    app.add_option("--pdf-param", pdfParameters, "parameter of the --pdf warp (repeatable; default: WARP's)");
    app.add_option("--samples-per-cell", samplesPerCell, "samples per histogram cell (default 1000)")
        ->check(integerIn(1, 100000));
    app.add_option("-t,--threads", threads, "threads for integrating the expected counts (default: all cores)")
        ->check(integerIn(1, 1024));
    auto finish = [&] {
        try {
            sampled = makeWarp(warpName, parameters, angle);
            const bool otherPdf = !pdfName.empty() || !pdfParameters.empty();
            reference = otherPdf ? makeWarp(pdfName.empty() ? warpName : pdfName,
                                            pdfParameters.empty() ? parameters : pdfParameters, angle)
                                 : sampled;
        } catch (const NoriException &e) {
            throw UsageError(e.what());
        }
        if (reference.spherical != sampled.spherical)
            throw UsageError(fmt::format("--pdf {} and {} do not share a domain", reference.name, sampled.name));
    };
    if (std::optional<int> status = cli.parse(argc, argv, finish)) return *status;

    try {
        if (threads == 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        std::printf("Testing warp %s%s\n", sampled.name.c_str(),
                    sampled.parameters.empty() ? "" : (", " + sampled.parameters).c_str());
        HypothesisResult result = testWarp(sampled, reference, samplesPerCell);
        std::fputs(result.report.c_str(), stdout);
        std::puts(result.accepted ? "warptest passed" : "warptest failed");
        return result.accepted ? 0 : 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "nori-warptest: %s\n", oneLine(e.what()).c_str());
        return 1;
    }
}
