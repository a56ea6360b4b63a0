/// \file warptest.cpp
/// \brief `nori-warptest WARP [PARAM...]`: chi^2 test of a warping function against its pdf.
/// Exit status 0 when the test passes, 1 when it fails, 2 for a usage error.
#include "validation/warp_catalog.h"
#include <charconv>
#include <cstdio>
#include <fmt/ranges.h>
#include <tbb/global_control.h>

using namespace nori;

namespace {

struct Arguments {
    std::string warp;
    std::vector<float> parameters;
    std::string pdfWarp;                 ///< --pdf: test against another warp's density
    std::vector<float> pdfParameters;    ///< --pdf-param (repeatable)
    float angle = 0.0f;                  ///< --angle: microfacet_brdf incident angle (degrees)
    int samplesPerCell = 1000;
    int threads = 0;
    bool help = false;
};

std::string usage() {
    return fmt::format(
        "Usage: nori-warptest [options] WARP [PARAM...]\n"
        "chi^2 test of a warping function's samples against its pdf; exit 0 when it passes.\n\n"
        "WARP: {}\n"
        "  beckmann ALPHA, microfacet_brdf ALPHA [KD] take parameters; the others none.\n\n"
        "Options:\n"
        "  --angle DEG          incident angle for microfacet_brdf (default 0)\n"
        "  --pdf WARP           expected counts from another warp's pdf (a test that must fail)\n"
        "  --pdf-param P        parameter of the --pdf warp (repeatable; default: the same as WARP's)\n"
        "  --samples-per-cell N samples per histogram cell (default 1000)\n"
        "  -t, --threads N      threads for the integration of expected counts (default: all)\n"
        "  -h, --help           this text\n",
        fmt::join(warpNames(), ", "));
}

float parseNumber(const std::string &text, const std::string &what) {
    float value = 0.0f;
    const char *begin = text.data(), *end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(begin, end, value);
    if (ec != std::errc() || ptr != end || text.empty() || !std::isfinite(value))
        throw NoriException("{} '{}' is not a number", what, text.substr(0, 60));
    return value;
}

int parseCount(const std::string &text, const std::string &what, int lo, int hi) {
    int value = 0;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size() || text.empty() || value < lo || value > hi)
        throw NoriException("{} must be an integer in [{}, {}], got '{}'", what, lo, hi, text.substr(0, 60));
    return value;
}

Arguments parseArguments(const std::vector<std::string> &args) {
    Arguments a;
    bool onlyPositional = false;
    std::vector<std::string> positional;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string &arg = args[i];
        auto value = [&]() -> const std::string & {
            if (i + 1 >= args.size()) throw NoriException("option {} needs a value", arg);
            return args[++i];
        };
        if (onlyPositional || arg.empty() || arg[0] != '-' || (arg.size() > 1 && std::isdigit((unsigned char)arg[1])))
            positional.push_back(arg);
        else if (arg == "--") onlyPositional = true;
        else if (arg == "-h" || arg == "--help") a.help = true;
        else if (arg == "--angle") a.angle = parseNumber(value(), "--angle");
        else if (arg == "--pdf") a.pdfWarp = value();
        else if (arg == "--pdf-param") a.pdfParameters.push_back(parseNumber(value(), "--pdf-param"));
        else if (arg == "--samples-per-cell") a.samplesPerCell = parseCount(value(), "--samples-per-cell", 1, 100000);
        else if (arg == "-t" || arg == "--threads") a.threads = parseCount(value(), "--threads", 1, 1024);
        else throw NoriException("unknown option '{}' (see --help)", arg.substr(0, 60));
    }
    if (a.help) return a;
    if (positional.empty()) throw NoriException("no warp given (see --help)");
    a.warp = positional[0];
    for (size_t i = 1; i < positional.size(); ++i) a.parameters.push_back(parseNumber(positional[i], "parameter"));
    return a;
}

} // namespace

int main(int argc, char **argv) {
    Arguments args;
    NamedWarp sampled, reference;
    try {
        args = parseArguments(std::vector<std::string>(argv + 1, argv + argc));
        if (args.help) {
            std::fputs(usage().c_str(), stdout);
            return 0;
        }
        sampled = makeWarp(args.warp, args.parameters, args.angle);
        reference = args.pdfWarp.empty() && args.pdfParameters.empty()
                        ? sampled
                        : makeWarp(args.pdfWarp.empty() ? args.warp : args.pdfWarp,
                                   args.pdfParameters.empty() ? args.parameters : args.pdfParameters, args.angle);
        if (reference.spherical != sampled.spherical)
            throw NoriException("--pdf {} and {} do not share a domain", reference.name, sampled.name);
    } catch (const NoriException &e) {
        std::fprintf(stderr, "nori-warptest: %s\n", e.what());
        return 2;
    }
    try {
        const int threads = args.threads > 0 ? args.threads : int(std::max(1u, std::thread::hardware_concurrency()));
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        std::printf("Testing warp %s%s\n", sampled.name.c_str(),
                    sampled.parameters.empty() ? "" : (", " + sampled.parameters).c_str());
        HypothesisResult result = testWarp(sampled, reference, args.samplesPerCell);
        std::fputs(result.report.c_str(), stdout);
        std::puts(result.accepted ? "warptest passed" : "warptest failed");
        return result.accepted ? 0 : 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "nori-warptest: %s\n", e.what());
        return 1;
    }
}
