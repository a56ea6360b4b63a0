/// \file image_diff.h
/// \brief How far apart two renders of one scene are (nori-bench render mode, nori-imgdiff).
#pragma once

#include <nori/bitmap.h>
#include <cstddef>

namespace nori::bench {

/// \brief Differences between a test image and a reference of the same size, over all
/// pixels and the three channels. "Relative" figures divide by the reference's mean.
struct ImageDiff {
    size_t pixels = 0;
    double meanRef = 0.0, meanTest = 0.0;  ///< mean over pixels and channels
    double rmse = 0.0;                     ///< sqrt(mean over pixels and channels of (test - ref)^2)
    double maxAbs = 0.0;                   ///< largest |test - ref| of any channel
    size_t differingPixels = 0;            ///< pixels with any channel not bitwise equal
    size_t visiblePixels = 0;              ///< pixels with a channel off by more than 1% of meanRef

    double rmseRel() const { return meanRef > 0.0 ? rmse / meanRef : 0.0; }
    double maxAbsRel() const { return meanRef > 0.0 ? maxAbs / meanRef : 0.0; }
    double differingFraction() const { return pixels ? double(differingPixels) / double(pixels) : 0.0; }
    double visibleFraction() const { return pixels ? double(visiblePixels) / double(pixels) : 0.0; }

    /// \brief Compare \p test with \p ref; throws NoriException if their sizes differ.
    static ImageDiff compute(const Bitmap &ref, const Bitmap &test);
    /// \brief |test - ref| per channel, scaled by \p gain (for a PNG of where they differ).
    static Bitmap absDifference(const Bitmap &ref, const Bitmap &test, float gain);
};

} // namespace nori::bench
