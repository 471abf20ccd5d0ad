#include "image/irradiance_weights.h"

#include "core/errors.h"
#include "image/envmap_layout.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh {
namespace {

// Sum of the weights of normal n over the rows [rowBegin, rowEnd).
double sumOverRows(const std::vector<double>& w, int width, int rowBegin, int rowEnd, int n) {
    double sum = 0.0;
    for (int r = rowBegin; r < rowEnd; ++r)
        for (int c = 0; c < width; ++c) sum += w[(std::size_t(r) * width + c) * kAxisNormals + n];
    return sum;
}

TEST(IrradianceWeights, EachNormalSeesPiOverItsHemisphere) {
    // The cosine over a hemisphere integrates to pi: a constant sky of 1 gives E = pi.
    const int width = 240, height = 120;
    const std::vector<double> w = axisIrradianceWeights(width, height);
    ASSERT_EQ(w.size(), std::size_t(width) * height * kAxisNormals);
    for (int n = 0; n < kAxisNormals; ++n)
        EXPECT_NEAR(sumOverRows(w, width, 0, height, n), M_PI, 2e-3 * M_PI) << "normal " << n;
}

TEST(IrradianceWeights, NormalsSeeOnlyTheirOwnSide) {
    const int width = 120, height = 60;
    const std::vector<double> w = axisIrradianceWeights(width, height);
    const int up = int(AxisNormal::MinusY), down = int(AxisNormal::PlusY);
    // Row 0 looks up (-y): the upper half of the map lights the normal facing up only.
    EXPECT_NEAR(sumOverRows(w, width, 0, height / 2, up), M_PI, 2e-3 * M_PI);
    EXPECT_EQ(sumOverRows(w, width, 0, height / 2, down), 0.0);
    // Column 3W/4 looks along +x: it weighs +x, never -x.
    const std::size_t p = std::size_t(height / 2) * width + 3 * width / 4;
    EXPECT_GT(w[p * kAxisNormals + int(AxisNormal::PlusX)], 0.0);
    EXPECT_EQ(w[p * kAxisNormals + int(AxisNormal::MinusX)], 0.0);
}

TEST(IrradianceWeights, RefusesAnEmptySize) {
    EXPECT_THROW(axisIrradianceWeights(0, 10), InputError);
    EXPECT_THROW(axisIrradianceWeights(10, -1), InputError);
}

}  // namespace
}  // namespace lh
