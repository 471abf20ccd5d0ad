#include "vdb/mantissa_rounding.h"

#include "core/errors.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

namespace lh {
namespace {

std::uint32_t bitsOf(float x) {
    std::uint32_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
}

// With 2 mantissa bits the values between 1 and 2 are 1, 1.25, 1.5 and 1.75.
TEST(MantissaRounding, RoundsToTheNearestRepresentableValue) {
    EXPECT_EQ(roundToMantissaBits(1.3f, 2), 1.25f);
    EXPECT_EQ(roundToMantissaBits(1.4f, 2), 1.5f);
    EXPECT_EQ(roundToMantissaBits(-1.4f, 2), -1.5f);
    EXPECT_EQ(roundToMantissaBits(1.875f, 2), 2.0f);   // a tie goes away from zero, to 2^1
    EXPECT_EQ(roundToMantissaBits(0.65f, 2), 0.625f);  // 1.3 x 2^-1
    EXPECT_EQ(roundToMantissaBits(0.0f, 5), 0.0f);
    EXPECT_EQ(roundToMantissaBits(1.0f / 3.0f, 22), 1.0f / 3.0f + std::ldexp(1.0f, -25));
}

TEST(MantissaRounding, StaysWithinItsRelativeBoundAndZeroesTheDroppedBits) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> mantissa(1.0f, 2.0f);
    std::uniform_int_distribution<int> exponent(-30, 30);
    for (int bits : {1, 4, 7, 9, 22}) {
        const std::uint32_t dropped = (std::uint32_t(1) << (23 - bits)) - 1;
        for (int i = 0; i < 2000; ++i) {
            const float x = std::ldexp(mantissa(rng), exponent(rng)) * (i % 2 ? -1.0f : 1.0f);
            const float r = roundToMantissaBits(x, bits);
            EXPECT_LE(std::abs(double(r) - x), std::ldexp(std::abs(double(x)), -(bits + 1)))
                << x << " at " << bits << " bits";
            EXPECT_EQ(bitsOf(r) & dropped, 0u) << x << " at " << bits << " bits";
        }
    }
}

TEST(MantissaRounding, StaysFiniteAndRefusesImpossibleBitCounts) {
    const float big = roundToMantissaBits(FLT_MAX, 3);
    EXPECT_TRUE(std::isfinite(big));
    EXPECT_GT(big, 0.5f * FLT_MAX);
    EXPECT_TRUE(std::isnan(roundToMantissaBits(std::numeric_limits<float>::quiet_NaN(), 3)));
    EXPECT_THROW(roundToMantissaBits(1.0f, 0), InputError);
    EXPECT_THROW(roundToMantissaBits(1.0f, 23), InputError);
    EXPECT_NO_THROW(validateMantissaBits(0, true));  // 0: no rounding
    EXPECT_NO_THROW(validateMantissaBits(22, false));
    EXPECT_NO_THROW(validateMantissaBits(9, true));
    EXPECT_THROW(validateMantissaBits(10, true), InputError);  // half keeps 10 bits anyway
    EXPECT_THROW(validateMantissaBits(-1, false), InputError);
}

TEST(MantissaRounding, RoundsVoxelsAndTilesOfBothGridTypes) {
    openvdb::initialize();
    openvdb::FloatGrid density(0.0f);
    density.tree().setValueOn(openvdb::Coord(1, 2, 3), 1.3f);
    density.tree().addTile(1, openvdb::Coord(64, 0, 0), 1.4f, true);  // one 8^3 tile
    roundGridToMantissaBits(density, 2);
    EXPECT_EQ(density.tree().getValue(openvdb::Coord(1, 2, 3)), 1.25f);
    EXPECT_EQ(density.tree().getValue(openvdb::Coord(66, 3, 5)), 1.5f);
    openvdb::Vec3SGrid colour(openvdb::Vec3s(0.0f));
    colour.tree().setValueOn(openvdb::Coord(0, 0, 0), openvdb::Vec3s(1.3f, -1.4f, 0.65f));
    roundGridToMantissaBits(colour, 2);
    EXPECT_EQ(colour.tree().getValue(openvdb::Coord(0, 0, 0)),
              openvdb::Vec3s(1.25f, -1.5f, 0.625f));
}

}  // namespace
}  // namespace lh
