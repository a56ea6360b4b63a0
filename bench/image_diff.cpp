/// \file image_diff.cpp
/// \brief Image difference statistics.
#include "image_diff.h"
#include <algorithm>
#include <cmath>

namespace nori::bench {

namespace {
void checkSizes(const Bitmap &ref, const Bitmap &test) {
    if (ref.size() != test.size())
        throw NoriException("images differ in size: {}x{} and {}x{}", ref.width(), ref.height(), test.width(),
                            test.height());
}
} // namespace

ImageDiff ImageDiff::compute(const Bitmap &ref, const Bitmap &test) {
    checkSizes(ref, test);
    ImageDiff d;
    d.pixels = ref.pixels().size();
    if (d.pixels == 0) return d;
    // Sums in double: a 1-megapixel image has 3M terms.
    double sumRef = 0.0, sumTest = 0.0, sumSq = 0.0;
    for (size_t i = 0; i < d.pixels; ++i) {
        const Color3f &a = ref.pixels()[i], &b = test.pixels()[i];
        for (int c = 0; c < 3; ++c) {
            double diff = double(b[c]) - double(a[c]);
            sumRef += a[c];
            sumTest += b[c];
            sumSq += diff * diff;
            d.maxAbs = std::max(d.maxAbs, std::fabs(diff));
        }
    }
    const double n = 3.0 * double(d.pixels);
    d.meanRef = sumRef / n;
    d.meanTest = sumTest / n;
    d.rmse = std::sqrt(sumSq / n);
    const double visible = 0.01 * d.meanRef;
    for (size_t i = 0; i < d.pixels; ++i) {
        const Color3f &a = ref.pixels()[i], &b = test.pixels()[i];
        bool differs = false, shows = false;
        for (int c = 0; c < 3; ++c) {
            differs = differs || a[c] != b[c];
            shows = shows || std::fabs(double(b[c]) - double(a[c])) > visible;
        }
        d.differingPixels += differs;
        d.visiblePixels += shows;
    }
    return d;
}

Bitmap ImageDiff::absDifference(const Bitmap &ref, const Bitmap &test, float gain) {
    checkSizes(ref, test);
    Bitmap out(ref.size());
    for (int y = 0; y < ref.height(); ++y)
        for (int x = 0; x < ref.width(); ++x)
            out(y, x) = gain * (test(y, x) - ref(y, x)).abs();
    return out;
}

} // namespace nori::bench
