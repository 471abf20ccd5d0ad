#include "core/fast_log.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace lh {
namespace {

TEST(FastLog, AgreesWithLibmOnOneToTwo) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> x(1.0, 2.0);
    double worstRelative = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const double v = x(rng);
        worstRelative =
            std::max(worstRelative, std::fabs(logOfOneToTwo(v) - std::log(v)) / std::log(v));
    }
    // The series' truncation (core/fast_log.h) is below 2.4e-10 relative; a wrong coefficient
    // would show at 1e-3 or worse.
    EXPECT_LT(worstRelative, 3e-10);
    EXPECT_NEAR(logOfOneToTwo(2.0), std::log(2.0), 2e-10);
}

TEST(FastLog, ExactAtOneAndNearIt) {
    EXPECT_EQ(logOfOneToTwo(1.0), 0.0);
    const double justAbove = 1.0 + 1e-12;  // ln(1 + e) ~ e: no cancellation in (x - 1)
    EXPECT_NEAR(logOfOneToTwo(justAbove), std::log(justAbove), 1e-22);
}

TEST(FastLog, HandsEverythingOutsideOneToTwoToLibm) {
    EXPECT_EQ(logOfOneToTwo(0.5), std::log(0.5));
    EXPECT_EQ(logOfOneToTwo(10.0), std::log(10.0));
    EXPECT_EQ(logOfOneToTwo(0.0), -std::numeric_limits<double>::infinity());
    EXPECT_TRUE(std::isnan(logOfOneToTwo(std::numeric_limits<double>::quiet_NaN())));
}

}  // namespace
}  // namespace lh
