#include "study/ray_budget.h"

#include "core/errors.h"
#include "image/envmap_layout.h"
#include "tests/support/test_volumes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace lh {
namespace {

RayBudgetOptions smallEnvmaps() {
    RayBudgetOptions o;
    o.width = 32, o.height = 16;
    return o;
}

// A box shell of homogeneous medium between |p|_inf = 1 and 2 (0.05 voxels), seen from its
// centre: a ray along d crosses 1 / max|d_i| of medium, 20 / max|d_i| voxels, whose alpha is
// 1 - exp(-1.5 x 0.05) = 0.072. No ray stops at T < 0.01 (the longest path, sqrt 3 units,
// leaves exp(-1.5 sqrt 3) = 0.07), so every ray crosses all of it.
TEST(RayBudget, ThinShellIsCrossedWholeAndCountedAsFog) {
    const RenderVolume volume(test::boxShellVolume());
    const RayBudgetOptions o = smallEnvmaps();
    const RayBudget b = measureRayBudget(volume, {Vec3d(0.0)}, o);
    double expectedVoxels = 0;  // mean over the envmap's rays
    for (int r = 0; r < o.height; ++r)
        for (int c = 0; c < o.width; ++c) {
            const Vec3d d = envmapPixelDirection(r, c, o.width, o.height);
            expectedVoxels += 20.0 / std::max({std::abs(d.x()), std::abs(d.y()), std::abs(d.z())});
        }
    expectedVoxels /= o.width * o.height;
    ASSERT_EQ(b.levels.size(), 1u);
    EXPECT_EQ(b.rays, o.width * o.height);
    EXPECT_NEAR(b.levels[0].voxelSize, 0.05, 1e-9);
    EXPECT_DOUBLE_EQ(b.levels[0].raysReaching, 1.0);
    // Trilinear interpolation spreads the inner face over one voxel (medium starts at 0.975).
    EXPECT_NEAR(b.mediumVoxelsPerRay(), expectedVoxels, 0.05 * expectedVoxels);
    EXPECT_GT(b.levels[0].mediumVoxels[1], 0.9 * b.mediumVoxelsPerRay());  // alpha 0.03-0.15
    EXPECT_DOUBLE_EQ(b.raysStopped, 0.0);
    // They leave with exp(-1.5 x 1 to 1.73) = 0.07-0.22 of their transmittance.
    EXPECT_DOUBLE_EQ(b.raysLeaving[0], 0.0);
    EXPECT_DOUBLE_EQ(b.raysLeaving[1] + b.raysLeaving[2], 1.0);
    EXPECT_GT(b.raysLeaving[1], 0.0);  // the corners' longest paths: below 0.1
    EXPECT_GT(b.raysLeaving[2], 0.0);  // the faces' shortest: above 0.1
    EXPECT_DOUBLE_EQ(b.raysLeaving[3], 0.0);
    EXPECT_DOUBLE_EQ(b.levels[0].lightShare, 1.0);
}

// The same shell, opaque (sigma 40 per unit: alpha 0.86 per voxel): every ray stops once it
// has crossed ln(100) / 40 = 0.115 units of it, 2.3 voxels.
TEST(RayBudget, OpaqueShellStopsEveryRayWithinItsOpticalDepth) {
    const RenderVolume volume(
        test::volumeOf({test::makeLevel(0.05, Vec3d(-2), openvdb::Coord(80), [](const Vec3d& p) {
            const double m = std::max({std::abs(p.x()), std::abs(p.y()), std::abs(p.z())});
            return m > 1.0 ? MediumSample{40.f, openvdb::Vec3s(1.f)} : MediumSample{};
        })}));
    const RayBudget b = measureRayBudget(volume, {Vec3d(0.0)}, smallEnvmaps());
    EXPECT_DOUBLE_EQ(b.raysStopped, 1.0);
    for (double leaving : b.raysLeaving) EXPECT_DOUBLE_EQ(leaving, 0.0);
    // The face's one-voxel ramp of density adds up to about half a voxel.
    EXPECT_GT(b.mediumVoxelsPerRay(), 2.3);
    EXPECT_LT(b.mediumVoxelsPerRay(), 3.3);
    EXPECT_GT(b.levels[0].mediumVoxels[3], 0.5 * b.mediumVoxelsPerRay());  // alpha 0.5-0.9
}

// Two nested levels: an opaque shell on the coarse level around an empty fine level. The rays
// cross the fine level without meeting medium, and all the light and medium is the coarse
// level's.
TEST(RayBudget, NestedLevelsAttributeMediumAndLightToTheLevelThatHoldsIt) {
    const auto shell = [](const Vec3d& p) {
        const double m = std::max({std::abs(p.x()), std::abs(p.y()), std::abs(p.z())});
        return m > 2.0 ? MediumSample{40.f, openvdb::Vec3s(1.f)} : MediumSample{};
    };
    const RenderVolume volume(
        test::volumeOf({test::makeLevel(0.1, Vec3d(-3.2), openvdb::Coord(64), shell),
                        test::makeLevel(0.05, Vec3d(-0.8), openvdb::Coord(32), shell)}));
    const RayBudget b = measureRayBudget(volume, {Vec3d(0.0)}, smallEnvmaps());
    ASSERT_EQ(b.levels.size(), 2u);
    EXPECT_DOUBLE_EQ(b.levels[0].raysReaching, 1.0);
    EXPECT_DOUBLE_EQ(b.levels[1].raysReaching, 1.0);
    EXPECT_DOUBLE_EQ(b.levels[1].mediumVoxelsTotal(), 0.0);
    EXPECT_DOUBLE_EQ(b.levels[1].lightShare, 0.0);
    EXPECT_DOUBLE_EQ(b.levels[0].lightShare, 1.0);
    EXPECT_DOUBLE_EQ(b.raysStopped, 1.0);
}

TEST(RayBudget, RefusesEnvmapsOfTheWrongShape) {
    RayBudgetOptions o;
    o.width = 30, o.height = 20;
    EXPECT_THROW(o.validate(), InputError);
    o = RayBudgetOptions{};
    o.minTransmittance = 0.0;
    EXPECT_THROW(o.validate(), InputError);
}

}  // namespace
}  // namespace lh
