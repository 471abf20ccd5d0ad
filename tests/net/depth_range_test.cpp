// Depth range from the stereo pair alone, against a textured plane at a known depth.
#include "net/depth_range.h"
#include "tests/net/net_test_scenes.h"

#include <gtest/gtest.h>

namespace lh::net {
namespace {

using test::planeCamera;
using test::renderPlane;

TEST(DepthRange, BracketsATexturedPlaneAtItsDepth) {
    for (double depth : {1.2, 3.0, 7.5}) {
        const PinholeCamera ref = planeCamera(128, 96),
                            src = planeCamera(128, 96, Vec3d(0.15, 0.02, 0.0));
        const DepthRange r =
            estimateDepthRange(renderPlane(ref, depth), renderPlane(src, depth), ref, src);
        EXPECT_FALSE(r.fallback);
        EXPECT_LT(r.near, depth) << depth;
        EXPECT_GT(r.far, depth) << depth;
        // A single plane gives a narrow range: about two candidate steps either side. A step is
        // 1.2 px of disparity here, so at 7.5 m (2 px of disparity) the range is wider.
        EXPECT_LT(r.far / r.near, depth < 5 ? 1.6 : 3.0) << depth;
    }
}

TEST(DepthRange, TexturelessPairFallsBackToTheDefaultRoom) {
    const PinholeCamera ref = planeCamera(64, 48), src = planeCamera(64, 48, Vec3d(0.1, 0.0, 0.0));
    ImageRGB flat(64, 48);
    std::fill(flat.pixels.begin(), flat.pixels.end(), 0.5f);
    const DepthRange r = estimateDepthRange(flat, flat, ref, src);
    EXPECT_TRUE(r.fallback);
    EXPECT_DOUBLE_EQ(r.near, kFallbackNear);
    EXPECT_DOUBLE_EQ(r.far, kFallbackFar);
}

}  // namespace
}  // namespace lh::net
