#include "core/fast_exp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace lh {
namespace {

// Relative difference in units of the last place of std::exp's answer.
double ulpsApart(double fast, double reference) {
    return std::fabs(fast - reference) / (std::nextafter(reference, INFINITY) - reference);
}

TEST(FastExp, AgreesWithLibmToAFewUlpOverTheWholeRange) {
    std::mt19937_64 rng(7);
    // Optical depths as the marcher meets them (1e-4 up to opacity), and the full range the
    // polynomial serves, both signs.
    std::uniform_real_distribution<double> small(0.0, 20.0), whole(-699.9, 699.9);
    double worst = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const double x = i % 2 ? small(rng) : whole(rng);
        worst = std::max(worst, ulpsApart(expOfNegative(x), std::exp(-x)));
    }
    EXPECT_LT(worst, 4.0);
}

TEST(FastExp, OneAtZeroAndPowersOfTwoAtMultiplesOfLn2) {
    EXPECT_EQ(expOfNegative(0.0), 1.0);
    EXPECT_EQ(expOfNegative(-0.0), 1.0);
    // Multiples of ln 2 land on k with r ~ 0: powers of two to the last bit or two.
    EXPECT_NEAR(expOfNegative(10 * std::log(2.0)), std::ldexp(1.0, -10),
                2e-16 * std::ldexp(1.0, -10));
}

TEST(FastExp, HandsTheEdgesToLibm) {
    EXPECT_EQ(expOfNegative(std::numeric_limits<double>::infinity()), 0.0);
    EXPECT_EQ(expOfNegative(-std::numeric_limits<double>::infinity()),
              std::numeric_limits<double>::infinity());
    EXPECT_TRUE(std::isnan(expOfNegative(std::numeric_limits<double>::quiet_NaN())));
    EXPECT_EQ(expOfNegative(800.0), std::exp(-800.0));  // subnormal
    EXPECT_EQ(expOfNegative(1e6), 0.0);                 // underflow
    // Either side of the switch to libm.
    EXPECT_LT(ulpsApart(expOfNegative(699.99), std::exp(-699.99)), 4.0);
    EXPECT_EQ(expOfNegative(700.0), std::exp(-700.0));
}

}  // namespace
}  // namespace lh
