// Expanding a volume's lamps and windows: known answers on single voxels of a cube, as
// training and predict apply the gain.
#include "net/highlight_gain.h"
#include "core/errors.h"
#include "net/volume_render.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace lh::net {
namespace {

// A cube [1, 4, 1, 1, 3] (rgb, alpha) of three voxels: a grey wall, a white lamp of luminance
// 2 and an orange lamp (3, 1.5, 0), whose luminance is 0.2126 * 3 + 0.7152 * 1.5 = 1.7106.
torch::Tensor threeVoxels() {
    return torch::tensor({0.5f, 2.f, 3.f, 0.5f, 2.f, 1.5f, 0.5f, 2.f, 0.f, 0.3f, 0.6f, 0.9f})
        .view({1, 4, 1, 1, 3});
}

double at(const torch::Tensor& cube, int channel, int x) {
    return cube[0][channel][0][0][x].item<double>();
}

TEST(HighlightGain, ScalesOnlyWhatIsAboveWhiteAndKeepsTheHue) {
    const auto cube = threeVoxels();
    const auto v = expandHighlightsInCubes({cube}, 10.0)[0];
    // The wall is below white: unchanged.
    for (int c = 0; c < 3; ++c) EXPECT_EQ(at(v, c, 0), 0.5);
    // Luminance 2 -> 1 + 10 * (2 - 1) = 11, grey stays grey.
    EXPECT_NEAR(at(v, 0, 1), 11.0, 1e-4);
    EXPECT_NEAR(at(v, 2, 1), 11.0, 1e-4);
    // Luminance 1.7106 -> 8.106: every channel times 8.106 / 1.7106, so the hue is kept.
    const double y = 0.2126 * 3 + 0.7152 * 1.5, scale = (1 + 10 * (y - 1)) / y;
    EXPECT_NEAR(at(v, 0, 2), 3 * scale, 1e-4);
    EXPECT_NEAR(at(v, 1, 2), 1.5 * scale, 1e-4);
    EXPECT_EQ(at(v, 2, 2), 0.0);
    // Alpha is the volume's shape: untouched.
    for (int x = 0; x < 3; ++x) EXPECT_EQ(at(v, 3, x), at(cube, 3, x));
}

TEST(HighlightGain, TheGradientReachesTheColours) {
    auto cube = threeVoxels().requires_grad_(true);
    expandHighlightsInCubes({cube}, 10.0)[0].sum().backward();
    EXPECT_TRUE(torch::isfinite(cube.grad()).all().item<bool>());
    EXPECT_NEAR(cube.grad()[0][0][0][0][0].item<double>(), 1.0, 1e-6);  // the wall: identity
    EXPECT_GT(cube.grad()[0][0][0][0][1].item<double>(), 5.0);          // the lamp: about 10
}

TEST(HighlightGain, GainOneChangesNothingAndBadGainsAreRefused) {
    const auto cube = threeVoxels();
    EXPECT_TRUE(expandHighlightsInCubes({cube}, 1.0)[0].is_same(cube));
    for (double bad :
         {0.5, 0.0, -3.0, kMaxHighlightGain * 2, std::numeric_limits<double>::quiet_NaN(),
          std::numeric_limits<double>::infinity()})
        EXPECT_THROW(validateHighlightGain(bad), InputError) << bad;
}

TEST(HighlightGain, AKneeExpandsOnlyWhatIsAboveIt) {
    const auto cube = threeVoxels();
    const double knee = 1.8;
    const auto v = expandHighlightsInCubes({cube}, 10.0, knee)[0];
    // The orange lamp (luminance 1.7106) is above white but below the knee: unchanged.
    EXPECT_EQ(at(v, 0, 2), 3.0);
    EXPECT_EQ(at(v, 1, 2), 1.5);
    // The grey lamp: 1.8 + 10 * (2 - 1.8) = 3.8, grey stays grey.
    EXPECT_NEAR(at(v, 0, 1), 3.8, 1e-4);
    EXPECT_NEAR(at(v, 1, 1), 3.8, 1e-4);
    // Continuous at the knee: a voxel just above it barely changes.
    const auto justAbove = torch::tensor({1.81f, 1.81f, 1.81f, 0.5f}).view({1, 4, 1, 1, 1});
    EXPECT_NEAR(expandHighlightsInCubes({justAbove}, 10.0, knee)[0][0][0][0][0][0].item<double>(),
                1.8 + 10 * 0.01, 1e-4);
    // Knee 1 is the plain gain.
    EXPECT_TRUE(torch::allclose(expandHighlightsInCubes({cube}, 10.0, 1.0)[0],
                                expandHighlightsInCubes({cube}, 10.0)[0]));
}

TEST(HighlightGain, BadKneesAreRefused) {
    EXPECT_NO_THROW(validateHighlightKnee(1.0));
    EXPECT_NO_THROW(validateHighlightKnee(kMaxHighlightKnee));
    for (double bad :
         {0.99, 0.0, -1.0, kMaxHighlightKnee * 1.01, std::numeric_limits<double>::quiet_NaN(),
          std::numeric_limits<double>::infinity()})
        EXPECT_THROW(validateHighlightKnee(bad), InputError) << bad;
}

}  // namespace
}  // namespace lh::net
