#include "image/photo_clipping.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace lh {
namespace {

// Metering for the highlights: 100 grey pixels of 0.01, 0.02, ..., 1.00; at most 5% may clip, so
// the exposure puts 0.95 at exactly 1 and only 0.96-1.00 above it.
TEST(PhotoClipping, MeteringForHighlightsClipsAtMostTheGivenFraction) {
    ImageRGB ramp(100, 1);
    for (int i = 0; i < 100; ++i) std::fill_n(&ramp.pixels[3 * i], 3, 0.01f * float(i + 1));
    const double white[3] = {1.0, 1.0, 1.0};
    const double exposure = exposureClippingAtMost(ramp, white, 0.05);
    EXPECT_NEAR(exposure, 1.0 / 0.95, 1e-5);
    const auto clippedAt = [&](double e) {
        int clipped = 0;
        for (int i = 0; i < 100; ++i) clipped += ramp.pixels[3 * i] * e > 1.0 + 1e-9;
        return clipped;
    };
    EXPECT_EQ(clippedAt(exposure), 5);
    EXPECT_EQ(clippedAt(exposure * 1.005), 6) << "a brighter exposure would clip more than 5%";
    // White balance counts: with red gained 2x, red clips first, at half the exposure.
    const double redder[3] = {2.0, 1.0, 1.0};
    EXPECT_NEAR(exposureClippingAtMost(ramp, redder, 0.05), 0.5 / 0.95, 1e-5);
    // Nothing may clip: the brightest pixel lands at 1.
    EXPECT_NEAR(exposureClippingAtMost(ramp, white, 0.0), 1.0, 1e-5);
    // A black photo clips at no exposure.
    EXPECT_TRUE(std::isinf(exposureClippingAtMost(ImageRGB(4, 4), white, 0.05)));
}

// The clipped pixels and their true brightness: a lamp of 40 and a pale wall of (1.2, 0.9, 0.6)
// clip at exposure 1, a grey of 0.5 does not; at exposure 0.5 only the lamp clips.
TEST(PhotoClipping, ClippedLuminancesAreThoseOfThePixelsAboveOne) {
    ImageRGB photo(3, 1);
    photo.pixels = {40.f, 40.f, 40.f, 1.2f, 0.9f, 0.6f, 0.5f, 0.5f, 0.5f};
    const std::vector<double> atOne = clippedLuminances(photo, 1.0);
    ASSERT_EQ(atOne.size(), 2u);
    EXPECT_NEAR(atOne[0], 40.0, 1e-4);
    EXPECT_NEAR(atOne[1], 0.2126 * 1.2 + 0.7152 * 0.9 + 0.0722 * 0.6, 1e-6)
        << "a pixel clips on its brightest channel, and its luminance may be below 1";
    const std::vector<double> atHalf = clippedLuminances(photo, 0.5);
    ASSERT_EQ(atHalf.size(), 1u);
    EXPECT_NEAR(atHalf[0], 20.0, 1e-4);
    EXPECT_TRUE(clippedLuminances(photo, 0.01).empty());
}

}  // namespace
}  // namespace lh
