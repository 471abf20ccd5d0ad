#include "image/srgb8.h"

#include "image/image_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace lh {
namespace {

TEST(Srgb8, KnownCodes) {
    EXPECT_EQ(srgb8FromLinear(0.0f), 0);
    EXPECT_EQ(srgb8FromLinear(1.0f), 255);
    // Linear 0.5 is sRGB 0.7354: 187.5 rounds to 188; 18% grey is code 118.
    EXPECT_EQ(srgb8FromLinear(0.5f), 188);
    EXPECT_EQ(srgb8FromLinear(0.18f), 118);
    EXPECT_FLOAT_EQ(linearFromSrgb8(0), 0.0f);
    EXPECT_FLOAT_EQ(linearFromSrgb8(255), 1.0f);
    EXPECT_NEAR(linearFromSrgb8(188), 0.5029, 1e-4);
}

TEST(Srgb8, OutOfRangeAndNonFiniteValuesClamp) {
    EXPECT_EQ(srgb8FromLinear(-3.0f), 0);
    EXPECT_EQ(srgb8FromLinear(40.0f), 255);
    EXPECT_EQ(srgb8FromLinear(std::numeric_limits<float>::infinity()), 255);
    EXPECT_EQ(srgb8FromLinear(std::nanf("")), 0);
}

TEST(Srgb8, EveryCodeSurvivesARoundTripAndDecodingIsMonotonic) {
    for (int code = 0; code < 256; ++code) {
        EXPECT_EQ(srgb8FromLinear(linearFromSrgb8(std::uint8_t(code))), code);
        EXPECT_FLOAT_EQ(linearFromSrgb8(std::uint8_t(code)), srgbDecode(float(code) / 255.0f));
        if (code > 0)
            EXPECT_GT(linearFromSrgb8(std::uint8_t(code)), linearFromSrgb8(std::uint8_t(code - 1)));
    }
}

}  // namespace
}  // namespace lh
