// Each edit with a known answer in the grids: the voxels it changes, the values it bounds
// (volume_edit_envmaps_test.cpp: what rendered envmaps and rays see).
#include "vdb/volume_edit.h"

#include "core/errors.h"
#include "tests/support/test_volumes.h"
#include "tests/vdb/edit_volumes.h"

#include <gtest/gtest.h>

#include <cstddef>

namespace lh {
namespace {

using test::emptyVolume;
using test::uniformVolume;

// Each edit says how many voxels it changed, so that an edit that misses every voxel centre
// (outside the volume, or between centres) can be refused instead of reported as applied.
TEST(VolumeEdit, EditsCountTheVoxelsTheyChange) {
    LightingVolume v = emptyVolume();
    const WorldBox outside{Vec3d(100), Vec3d(101)};
    EXPECT_EQ(addEmissiveBox(v, outside, openvdb::Vec3s(1), 10.f), 0u);
    EXPECT_EQ(eraseBox(v, outside), 0u);
    EXPECT_EQ(addEmissiveSphere(v, Vec3d(100), 0.5, openvdb::Vec3s(1), 10.f), 0u);
    const std::size_t added = addEmissiveBox(v, {Vec3d(2, -0.5, -0.5), Vec3d(3, 0.5, 0.5)},
                                             openvdb::Vec3s(4, 0, 0), 100.f);
    EXPECT_GT(added, 0u);
    EXPECT_EQ(
        added,
        std::size_t(v.activeVoxelCount()));  // the volume was empty: every painted voxel is new
    EXPECT_EQ(eraseBox(v, {Vec3d(2, -0.5, -0.5), Vec3d(3, 0.5, 0.5)}), added);
    EXPECT_EQ(v.activeVoxelCount(), 0u);
}

TEST(VolumeEdit, ClampBoundsValues) {
    LightingVolume v = uniformVolume(1e6f, openvdb::Vec3s(1e5f, 2.f, 0.5f));
    clampValues(v, 10.f, 1.f);
    EXPECT_EQ(v.levels[1].density->tree().getValue(openvdb::Coord(3)), 10.f);
    EXPECT_EQ(v.levels[1].color->tree().getValue(openvdb::Coord(3)),
              openvdb::Vec3s(1.f, 1.f, 0.5f));
}

}  // namespace
}  // namespace lh
