#include "image/envmap_layout.h"

#include <gtest/gtest.h>

namespace lh {
namespace {

constexpr int W = 240, H = 120;

TEST(EnvmapLayout, NamedDirectionsLandOnConventionPixels) {
    // Centre column looks forward, 3W/4 right, W/4 left (continuous coordinates).
    EXPECT_NEAR((envmapDirection(H / 2.0, W / 2.0, W, H) - Vec3d(0, 0, 1)).length(), 0, 1e-12);
    EXPECT_NEAR((envmapDirection(H / 2.0, 3 * W / 4.0, W, H) - Vec3d(1, 0, 0)).length(), 0, 1e-12);
    EXPECT_NEAR((envmapDirection(H / 2.0, W / 4.0, W, H) - Vec3d(-1, 0, 0)).length(), 0, 1e-12);
    EXPECT_NEAR((envmapDirection(0.0, 17.0, W, H) - Vec3d(0, -1, 0)).length(), 0, 1e-12);  // up
    EXPECT_NEAR((envmapDirection(H, 17.0, W, H) - Vec3d(0, 1, 0)).length(), 0, 1e-12);     // down
    // First and last pixel columns look backward (-z).
    EXPECT_LT(envmapPixelDirection(H / 2, 0, W, H).z(), -0.99);
    EXPECT_LT(envmapPixelDirection(H / 2, W - 1, W, H).z(), -0.99);
    // Row 0 looks up.
    EXPECT_LT(envmapPixelDirection(0, 100, W, H).y(), -0.99);
}

TEST(EnvmapLayout, PixelDirectionPixelRoundTrip) {
    for (int r = 0; r < H; ++r)
        for (int c = 0; c < W; ++c) {
            const Vec3d d = envmapPixelDirection(r, c, W, H);
            EXPECT_NEAR(d.length(), 1.0, 1e-12);
            const EnvmapCoord back = envmapCoordinate(d, W, H);
            ASSERT_NEAR(back.row, r + 0.5, 1e-9) << r << "," << c;
            ASSERT_NEAR(back.column, c + 0.5, 1e-9) << r << "," << c;
        }
}

}  // namespace
}  // namespace lh
