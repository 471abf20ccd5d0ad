// Expanding a volume's lamps and windows: known answers on single voxels, in the exported
// volume and in the training cubes alike.
#include "net/highlight_gain.h"
#include "core/errors.h"
#include "net/volume_render.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace lh::net {
namespace {

// One level of 4^3 voxels with three active ones: a grey wall, a white lamp of luminance 2 and
// an orange lamp (3, 1.5, 0), whose luminance is 0.2126 * 3 + 0.7152 * 1.5 = 1.7106.
LightingVolume threeVoxels() {
    VolumeLevel level;
    level.density = openvdb::FloatGrid::create(0.f);
    level.color = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    level.domain = openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(3));
    const openvdb::Coord wall(0, 0, 0), white(1, 0, 0), orange(2, 0, 0);
    for (const auto& [xyz, c] : {std::pair{wall, openvdb::Vec3s(0.5f, 0.5f, 0.5f)},
                                 std::pair{white, openvdb::Vec3s(2.f, 2.f, 2.f)},
                                 std::pair{orange, openvdb::Vec3s(3.f, 1.5f, 0.f)}}) {
        level.density->tree().setValueOn(xyz, 4.f);
        level.color->tree().setValueOn(xyz, c);
    }
    LightingVolume volume;
    volume.levels.push_back(level);
    return volume;
}

openvdb::Vec3s colourAt(const LightingVolume& v, int x) {
    return v.levels[0].color->tree().getValue(openvdb::Coord(x, 0, 0));
}

TEST(HighlightGain, ScalesOnlyWhatIsAboveWhiteAndKeepsTheHue) {
    LightingVolume v = threeVoxels();
    expandHighlights(v, 10.0);
    // The wall is below white: unchanged.
    EXPECT_EQ(colourAt(v, 0), openvdb::Vec3s(0.5f, 0.5f, 0.5f));
    // Luminance 2 -> 1 + 10 * (2 - 1) = 11, grey stays grey.
    EXPECT_NEAR(colourAt(v, 1)[0], 11.0, 1e-4);
    EXPECT_NEAR(colourAt(v, 1)[2], 11.0, 1e-4);
    // Luminance 1.7106 -> 8.106: every channel times 8.106 / 1.7106, so the hue is kept.
    const double y = 0.2126 * 3 + 0.7152 * 1.5, scale = (1 + 10 * (y - 1)) / y;
    EXPECT_NEAR(colourAt(v, 2)[0], 3 * scale, 1e-4);
    EXPECT_NEAR(colourAt(v, 2)[1], 1.5 * scale, 1e-4);
    EXPECT_EQ(colourAt(v, 2)[2], 0.f);
    // Densities are the volume's shape: untouched.
    EXPECT_EQ(v.levels[0].density->tree().getValue(openvdb::Coord(1, 0, 0)), 4.f);
}

TEST(HighlightGain, TheTrainingCubesGainAsTheExportedVolume) {
    // The same three voxels as a cube [1, 4, 1, 1, 3] (rgb, alpha): the same answers, alpha
    // untouched, and a gradient that reaches the colours.
    auto cube = torch::tensor({0.5f, 2.f, 3.f, 0.5f, 2.f, 1.5f, 0.5f, 2.f, 0.f, 0.3f, 0.6f, 0.9f})
                    .view({1, 4, 1, 1, 3})
                    .requires_grad_(true);
    const auto gained = expandHighlightsInCubes({cube}, 10.0)[0];
    LightingVolume v = threeVoxels();
    expandHighlights(v, 10.0);
    for (int x = 0; x < 3; ++x) {
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(gained[0][c][0][0][x].item<double>(), colourAt(v, x)[c], 1e-4)
                << "voxel " << x << " channel " << c;
        EXPECT_EQ(gained[0][3][0][0][x].item<float>(), cube[0][3][0][0][x].item<float>());
    }
    gained.sum().backward();
    EXPECT_TRUE(torch::isfinite(cube.grad()).all().item<bool>());
    EXPECT_NEAR(cube.grad()[0][0][0][0][0].item<double>(), 1.0, 1e-6);  // the wall: identity
    EXPECT_GT(cube.grad()[0][0][0][0][1].item<double>(), 5.0);          // the lamp: about 10
    EXPECT_TRUE(expandHighlightsInCubes({cube}, 1.0)[0].is_same(cube));
}

TEST(HighlightGain, GainOneChangesNothingAndBadGainsAreRefused) {
    LightingVolume v = threeVoxels();
    expandHighlights(v, 1.0);
    EXPECT_EQ(colourAt(v, 1), openvdb::Vec3s(2.f, 2.f, 2.f));
    for (double bad :
         {0.5, 0.0, -3.0, kMaxHighlightGain * 2, std::numeric_limits<double>::quiet_NaN(),
          std::numeric_limits<double>::infinity()}) {
        EXPECT_THROW(expandHighlights(v, bad), InputError) << bad;
        EXPECT_THROW(validateHighlightGain(bad), InputError) << bad;
    }
    EXPECT_EQ(colourAt(v, 1), openvdb::Vec3s(2.f, 2.f, 2.f));
}

}  // namespace
}  // namespace lh::net
