#include "render/view.h"

#include "core/errors.h"
#include "tests/support/test_volumes.h"
#include "vdb/example_volume.h"

#include <gtest/gtest.h>

namespace lh {
namespace {

TEST(View, WallFillsTheFrameAndBlockSitsOnTheRightSide) {
    // An opaque grey wall at z in [3, 3.5] and a red block to the right (+x) in front of it.
    const auto field = [](const Vec3d& p) {
        if (p.x() > 0.5 && p.x() < 1.0 && std::abs(p.y()) < 0.25 && p.z() > 2.0 && p.z() < 2.5)
            return MediumSample{60.f, openvdb::Vec3s(1, 0, 0)};
        if (p.z() > 3.0 && p.z() < 3.5) return MediumSample{60.f, openvdb::Vec3s(0.5f)};
        return MediumSample{};
    };
    const RenderVolume volume(test::volumeOf(
        {test::makeLevel(0.05, Vec3d(-4, -4, 0), openvdb::Coord(160, 160, 80), field)}));
    PinholeCamera cam = exampleCameras().ref;
    const ImageRGB img = renderView(volume, cam);
    // Top-left corner: the wall at 0.5 radiance.
    EXPECT_NEAR(img.at(5, 5)[0], 0.5, 1e-3);
    EXPECT_NEAR(img.at(5, 5)[1], 0.5, 1e-3);
    // The block projects to x = fx * 0.75 / 2.25 + cx, right of centre.
    const int u = int(cam.fx * 0.75 / 2.25 + cam.cx), v = int(cam.cy);
    EXPECT_NEAR(img.at(u, v)[0], 1.0, 1e-3);
    EXPECT_NEAR(img.at(u, v)[1], 0.0, 1e-3);
    // Mirror position on the left shows the wall, not the block.
    EXPECT_NEAR(img.at(cam.width - u, v)[1], 0.5, 1e-3);
}

TEST(View, ImpossibleCameraIsRefused) {
    const RenderVolume volume(makeExampleVolume(1, 8));
    PinholeCamera cam = exampleCameras().ref;
    cam.fx = -1;
    EXPECT_THROW(renderView(volume, cam), InputError);
}

}  // namespace
}  // namespace lh
