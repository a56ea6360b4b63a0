/// \file imgdiff.cpp
/// \brief nori-imgdiff: compare renders (OpenEXR) with a reference: means, their difference
/// with a standard error, RMSE, and the convergence rate of RMSE over samples per pixel.
//
//   nori-imgdiff REF.exr TEST.exr [TEST.exr ...] [--spp N,N,...] [--tile T] [--region X0,Y0,X1,Y1]
//                [--json FILE]
//
// For each test image: the mean over pixels and channels of the reference and of the test,
// their difference with a standard error and z = difference / error, the RMSE and the RMSE
// relative to the reference mean. The standard error comes from T x T tiles of the per-pixel
// difference (default 16): the reconstruction filter spreads a sample over neighbouring pixels,
// so single pixels are not independent but tiles nearly are. With --spp (one count per test
// image) it also fits log RMSE = a + b log spp by least squares and prints the slope b
// (-0.5 for an unbiased Monte Carlo estimator against an exact reference). --region compares
// only a rectangle given as fractions of the image (e.g. to leave out directly visible light
// sources, whose anti-aliased edges have the same large variance per sample under every
// integrator and would otherwise dominate the RMSE).
#include "image_diff.h"
#include <app/cli_app.h>
#include <nori/atomic_file.h>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace nori;
using nori::bench::ImageDiff;

namespace {

struct Row {
    std::string path;
    int spp = 0;
    ImageDiff diff;
    double meanDiff = 0.0, stdErr = 0.0;

    double z() const { return stdErr > 0.0 ? meanDiff / stdErr : 0.0; }
};

/// Mean difference (test - ref, averaged over channels) and its standard error from tile means.
void meanDifference(const Bitmap &ref, const Bitmap &test, int tile, Row &row) {
    std::vector<double> tiles;
    for (int y0 = 0; y0 < ref.height(); y0 += tile)
        for (int x0 = 0; x0 < ref.width(); x0 += tile) {
            double sum = 0.0;
            int n = 0;
            for (int y = y0; y < std::min(y0 + tile, ref.height()); ++y)
                for (int x = x0; x < std::min(x0 + tile, ref.width()); ++x, ++n)
                    sum += (test(y, x) - ref(y, x)).cast<double>().mean();
            tiles.push_back(sum / n);
        }
    // Tiles at the right and bottom edges may be smaller; weigh every tile alike (the
    // image mean differs from the tile mean by a negligible edge effect, so use the exact
    // image mean for the difference and the tiles only for its spread).
    double mean = 0.0;
    for (double t : tiles) mean += t;
    mean /= double(tiles.size());
    double var = 0.0;
    for (double t : tiles) var += (t - mean) * (t - mean);
    var /= std::max<double>(1.0, double(tiles.size()) - 1.0);
    row.meanDiff = row.diff.meanTest - row.diff.meanRef;
    row.stdErr = std::sqrt(var / double(tiles.size()));
}

/// The pixels of \p img in the rectangle [x0, x1) x [y0, y1) given as fractions of its size.
Bitmap cropFraction(const Bitmap &img, const std::vector<double> &r) {
    const int x0 = int(std::lround(r[0] * img.width())), y0 = int(std::lround(r[1] * img.height()));
    const int x1 = int(std::lround(r[2] * img.width())), y1 = int(std::lround(r[3] * img.height()));
    Bitmap out(x1 - x0, y1 - y0);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) out(y - y0, x - x0) = img(y, x);
    return out;
}

/// Least-squares slope of log(rmse) over log(spp).
double fitSlope(const std::vector<Row> &rows) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double n = double(rows.size());
    for (const Row &r : rows) {
        double x = std::log(double(r.spp)), y = std::log(r.diff.rmse);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

int run(int argc, char **argv) {
    CliApp cli("nori-imgdiff", "Compares OpenEXR renders with a reference: means, their difference with a "
                               "standard error, RMSE, and the slope of log RMSE over log spp.");
    CLI::App &app = cli.app();
    std::string refPath, jsonPath;
    std::vector<std::string> tests;
    std::vector<int> spp;
    std::vector<double> region;
    int tile = 16;
    app.add_option("reference", refPath, "reference image (OpenEXR)")->required()->check(CLI::ExistingFile);
    app.add_option("tests", tests, "images to compare with it (OpenEXR)")->required()->check(CLI::ExistingFile);
    app.add_option("--spp", spp, "samples per pixel of each test image (fits the RMSE slope)")
        ->delimiter(',')
        ->check(CLI::PositiveNumber);
    app.add_option("--tile", tile, "tile size for the standard error of the mean difference")
        ->check(CLI::Range(1, 4096));
    app.add_option("--region", region, "compare only this rectangle, as fractions of the image (0 <= X0 < X1 <= 1)")
        ->delimiter(',')
        ->expected(4)
        ->option_text("X0,Y0,X1,Y1");
    app.add_option("--json", jsonPath, "also write the figures as JSON")->option_text("FILE");
    auto finish = [&] {
        if (!spp.empty() && spp.size() != tests.size())
            throw UsageError(fmt::format("--spp lists {} counts for {} test images", spp.size(), tests.size()));
        if (!region.empty() &&
            !(region[0] >= 0.0 && region[0] < region[2] && region[2] <= 1.0 && region[1] >= 0.0 &&
              region[1] < region[3] && region[3] <= 1.0))
            throw UsageError("--region needs 0 <= X0 < X1 <= 1 and 0 <= Y0 < Y1 <= 1");
    };
    if (std::optional<int> status = cli.parse(argc, argv, finish)) return *status;

    Bitmap ref = Bitmap::loadEXR(refPath);
    const int fullWidth = ref.width(), fullHeight = ref.height();
    if (!region.empty()) ref = cropFraction(ref, region);
    if (ref.width() < 1 || ref.height() < 1) throw std::runtime_error("--region holds no pixel of " + refPath);
    std::vector<Row> rows;
    for (size_t i = 0; i < tests.size(); ++i) {
        Row row;
        row.path = tests[i];
        row.spp = spp.empty() ? 0 : spp[i];
        Bitmap test = Bitmap::loadEXR(tests[i]);
        if (test.width() != fullWidth || test.height() != fullHeight)
            throw std::runtime_error(fmt::format("{} is {}x{}, the reference {}x{}", tests[i], test.width(),
                                                 test.height(), fullWidth, fullHeight));
        if (!region.empty()) test = cropFraction(test, region);
        row.diff = ImageDiff::compute(ref, test);
        meanDifference(ref, test, tile, row);
        rows.push_back(row);
    }

    std::printf("reference %s: %dx%d, mean %.6g", refPath.c_str(), fullWidth, fullHeight, rows[0].diff.meanRef);
    if (!region.empty())
        std::printf(" (region x %.3g-%.3g, y %.3g-%.3g of the image: %dx%d pixels)", region[0], region[2], region[1],
                    region[3], ref.width(), ref.height());
    std::printf("\n\n");
    std::printf("| image | spp | mean | mean - ref | std. error | z | RMSE | RMSE / ref mean |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Row &r : rows)
        std::printf("| %s | %s | %.6g | %+.3g | %.2g | %+.2f | %.4g | %.4g |\n", r.path.c_str(),
                    r.spp ? std::to_string(r.spp).c_str() : "", r.diff.meanTest, r.meanDiff, r.stdErr, r.z(),
                    r.diff.rmse, r.diff.rmseRel());
    double slope = std::nan("");
    if (rows.size() >= 2 && !spp.empty()) {
        slope = fitSlope(rows);
        std::printf("\nfitted slope of log RMSE over log spp: %.3f (an unbiased estimator: -0.5)\n", slope);
    }

    if (!jsonPath.empty()) {
        nlohmann::ordered_json j;
        j["reference"] = refPath;
        j["width"] = ref.width();
        j["height"] = ref.height();
        j["tile"] = tile;
        if (!region.empty()) j["region"] = region;
        for (const Row &r : rows)
            j["images"].push_back({{"path", r.path}, {"spp", r.spp}, {"mean", r.diff.meanTest},
                                   {"mean_ref", r.diff.meanRef}, {"mean_diff", r.meanDiff}, {"std_error", r.stdErr},
                                   {"z", r.z()}, {"rmse", r.diff.rmse}, {"rmse_rel", r.diff.rmseRel()},
                                   {"max_abs", r.diff.maxAbs}});
        if (std::isfinite(slope)) j["slope"] = slope;
        AtomicFile::write(jsonPath, j.dump(2) + "\n");
    }
    return 0;
}

} // namespace

int main(int argc, char **argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "nori-imgdiff: %s\n", oneLine(e.what()).c_str());
        return 1;
    }
}
