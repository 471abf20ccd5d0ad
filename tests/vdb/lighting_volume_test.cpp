#include "vdb/lighting_volume.h"

#include "core/errors.h"
#include "tests/support/test_volumes.h"
#include "vdb/example_volume.h"

#include <gtest/gtest.h>

namespace lh {
namespace {

TEST(LightingVolume, FromLayoutHasNestedLevelsCoarsestFirst) {
    LightingVolume v = LightingVolume::fromLayout(VolumeLayout{14.0, 5, 32});
    ASSERT_EQ(v.levels.size(), 5u);
    for (std::size_t k = 0; k < v.levels.size(); ++k) {
        EXPECT_EQ(v.levels[k].density->getName(), densityGridName(int(k)));
        EXPECT_EQ(v.levels[k].color->getName(), colorGridName(int(k)));
        EXPECT_EQ(v.levels[k].color->getVectorType(), openvdb::VEC_INVARIANT);
        EXPECT_EQ(v.levels[k].density->getGridClass(), openvdb::GRID_FOG_VOLUME);
        if (k > 0) {
            EXPECT_LT(v.levels[k].voxelVolume(), v.levels[k - 1].voxelVolume());
        }
    }
    const WorldBox b = v.levels[1].worldBounds();
    EXPECT_NEAR(b.min.z(), 0.0, 1e-12);
    EXPECT_NEAR(b.max.z(), 7.0, 1e-12);
}

TEST(LightingVolume, FinestLevelAtNamesTheLevelThatDefinesThePoint) {
    // Level 0 spans [-4, 4]^3; level 1 [-2, 2] x [-2, 2] x [0, 4]; level 2 [-1, 1]^2 x [0, 2].
    const LightingVolume v = LightingVolume::fromLayout(VolumeLayout{8.0, 3, 8});
    EXPECT_EQ(finestLevelAt(v, Vec3d(0.0, 0.0, 0.5)), 2);
    EXPECT_EQ(finestLevelAt(v, Vec3d(1.5, 0.0, 0.5)), 1);   // beside the finest level
    EXPECT_EQ(finestLevelAt(v, Vec3d(0.0, 0.0, 3.0)), 1);   // beyond it
    EXPECT_EQ(finestLevelAt(v, Vec3d(0.0, 0.0, -3.0)), 0);  // behind the camera
    EXPECT_EQ(finestLevelAt(v, Vec3d(0.0, 0.0, 5.0)), -1);  // outside every level
    EXPECT_EQ(finestLevelAt(LightingVolume{}, Vec3d(0.0, 0.0, 0.5)), -1);
}

TEST(LightingVolume, FillLevelKeepsEmptySpaceInactive) {
    LightingVolume v = LightingVolume::fromLayout(VolumeLayout{8.0, 1, 16});
    // Half-voxel-aligned box: x in [0, 4) covers exactly 8 of 16 columns.
    v.fillLevel(0,
                test::boxField(Vec3d(0, -4, -4), Vec3d(4, 4, 4), {2.f, openvdb::Vec3s(1, 0, 0)}));
    EXPECT_EQ(v.levels[0].density->activeVoxelCount(), 8u * 16 * 16);
    EXPECT_EQ(v.levels[0].density->tree().getValue(openvdb::Coord(12, 3, 3)), 2.f);
    EXPECT_EQ(v.levels[0].color->tree().getValue(openvdb::Coord(12, 3, 3)),
              openvdb::Vec3s(1, 0, 0));
    EXPECT_FALSE(v.levels[0].density->tree().isValueOn(openvdb::Coord(3, 3, 3)));
}

TEST(LightingVolume, FinerIsDecidedByVoxelSizeNotOrder) {
    auto field = test::boxField(Vec3d(-1), Vec3d(1), {1.f, openvdb::Vec3s(1)});
    VolumeLevel fine = test::makeLevel(0.1, Vec3d(-1), openvdb::Coord(20), field);
    VolumeLevel coarse = test::makeLevel(0.4, Vec3d(-4), openvdb::Coord(20), field);
    LightingVolume v = test::volumeOf({fine, coarse});
    EXPECT_EQ(v.levels[0].density, coarse.density);
    EXPECT_EQ(v.levels[1].density, fine.density);
    EXPECT_THROW(test::volumeOf({coarse, test::makeLevel(0.4, Vec3d(0), openvdb::Coord(4), field)}),
                 InputError);
}

TEST(LightingVolume, ValidateRejectsMismatchedTransforms) {
    LightingVolume v = LightingVolume::fromLayout(VolumeLayout{8.0, 2, 8});
    v.levels[1].color->setTransform(openvdb::math::Transform::createLinearTransform(0.3));
    EXPECT_THROW(v.validate(), InputError);
}

TEST(LightingVolume, ExampleRoomHasContentInEveryLevel) {
    LightingVolume v = makeExampleVolume(5, 32);
    ASSERT_EQ(v.levels.size(), 5u);
    for (const auto& level : v.levels) EXPECT_GT(level.density->activeVoxelCount(), 0u);
    // The lamp is emissive and bright; the air at the camera is empty.
    EXPECT_GT(exampleRoomMedium(Vec3d(0, -1.3, 2.5)).color.x(), 5.f);
    EXPECT_EQ(exampleRoomMedium(Vec3d(0, 0, 0)).sigma, 0.f);
}

}  // namespace
}  // namespace lh
