// Observed masks from first-hit positions and the reference depth, on a scene whose answer is
// known: a wall at z = 4 m, hidden on the image's left half by a screen at z = 2 m.
#include "net/observed_mask.h"

#include "core/errors.h"

#include "tests/support/test_camera.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace lh::net {
namespace {

// 40x30 pixels, f = 20 px, principal point at the centre: x = 20 + 20 X / Z, y = 15 + 20 Y / Z.
PinholeCamera camera(const Vec3d& position = Vec3d(0.0)) {
    return test::centredCamera(40, 30, 20.0, position);
}

// Depth 2 (the screen) in columns 0..19, 4 (the wall) in columns 20..39.
ImageRGB screenAndWall() {
    ImageRGB depth(40, 30);
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) std::fill_n(depth.at(x, y), 3, x < 20 ? 2.f : 4.f);
    return depth;
}

// A 1-row "envmap" whose pixels saw the given first-hit points.
ImageRGB positions(const std::vector<Vec3d>& points) {
    ImageRGB image(int(points.size()), 1);
    for (std::size_t i = 0; i < points.size(); ++i)
        for (int c = 0; c < 3; ++c) image.pixels[3 * i + c] = float(points[i][c]);
    return image;
}

TEST(ObservedMask, ProjectsAndTestsAgainstTheDepthMap) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<Vec3d> points = {
        {0.5, 0.2, 4.0},   // on the wall, right half (pixel 22.5, 16): observed
        {-1.0, 0.0, 4.0},  // on the wall behind the screen (pixel 15): hidden
        {-1.0, 0.0, 2.0},  // on the screen itself (pixel 10): observed
        {0.0, 0.0, -1.0},  // behind the camera
        {10.0, 0.0, 4.0},  // right of the image (pixel 70)
        {0.0, -3.5, 4.0},  // above the image (pixel row -2.5)
        {nan, 0.0, 4.0},   // no hit
        {0.0, 0.0, 0.0},   // synth's "no hit": the camera centre, z = 0
        {0.5, 0.2, 4.09},  // 9 cm behind the wall: within 2% of 4 m + 2 cm = 10 cm
        {0.5, 0.2, 4.2},   // 20 cm behind the wall: hidden
        {-0.2, 0.0, 1.0},  // in front of the screen (pixel 16): nothing hides it
        {0.99, 0.0, 1.0},  // pixel column 39.8: the last column is inside
        {1.0, 0.0, 1.0},   // pixel column 40.0: the image's right edge is outside
    };
    const std::vector<std::uint8_t> expected = {1, 0, 1, 0, 0, 0, 0, 0, 1, 0, 1, 1, 0};
    EXPECT_EQ(observedMaskFromDepth(positions(points), camera(), screenAndWall()), expected);
}

TEST(ObservedMask, ToleranceIsRelativePlusAbsolute) {
    const ImageRGB behind = positions({{0.5, 0.2, 4.09}});
    DepthTolerance tight;
    tight.relative = 0.0;
    tight.absolute = 0.05;  // 4.09 > 4 + 0.05: hidden
    EXPECT_EQ(observedMaskFromDepth(behind, camera(), screenAndWall(), tight),
              std::vector<std::uint8_t>{0});
    tight.relative = 0.02;  // 4 + 0.08 + 0.05 = 4.13 > 4.09: seen
    EXPECT_EQ(observedMaskFromDepth(behind, camera(), screenAndWall(), tight),
              std::vector<std::uint8_t>{1});
}

TEST(ObservedMask, UsesTheReferencePoseAndSkipsMissingDepth) {
    // The camera moved 1 m along +x: the world point (1.5, 0.2, 4) is at (0.5, 0.2, 4) in its
    // frame, on the wall's visible half.
    const ImageRGB moved = positions({{1.5, 0.2, 4.0}, {0.0, 0.0, 4.0}});
    EXPECT_EQ(observedMaskFromDepth(moved, camera(Vec3d(1.0, 0.0, 0.0)), screenAndWall()),
              (std::vector<std::uint8_t>{1, 0}));
    // Where the depth map has no surface (infinite, or 0), nothing hides a point.
    ImageRGB open = screenAndWall();
    std::fill(open.pixels.begin(), open.pixels.end(), std::numeric_limits<float>::infinity());
    const ImageRGB far = positions({{-1.0, 0.0, 40.0}});
    EXPECT_EQ(observedMaskFromDepth(far, camera(), open), std::vector<std::uint8_t>{1});
    std::fill(open.pixels.begin(), open.pixels.end(), 0.f);
    EXPECT_EQ(observedMaskFromDepth(far, camera(), open), std::vector<std::uint8_t>{1});
}

TEST(ObservedMask, RejectsADepthMapOfAnotherSize) {
    try {
        observedMaskFromDepth(positions({{0, 0, 1}}), camera(), ImageRGB(20, 15));
        FAIL() << "depth map of the wrong size accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("20x15"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("40x30"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace lh::net
