// Each edit with a known answer: rendered envmaps and rays change exactly where and how they
// should.
#include "vdb/volume_edit.h"

#include "core/errors.h"
#include "image/envmap_layout.h"
#include "render/envmap.h"
#include "tests/support/test_volumes.h"
#include "tests/vdb/edit_volumes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh {
namespace {

using test::emptyVolume;
using test::uniformVolume;

float seen(const LightingVolume& v, const Vec3d& from, const Vec3d& dir, int channel = 0) {
    return float(marchRay(RenderVolume(v), from, dir.unit(), MarchOptions{0.5, 0.0, true})
                     .radiance[channel]);
}

TEST(VolumeEdit, AddedEmissiveBoxAppearsWhereItWasPut) {
    LightingVolume v = emptyVolume();
    addEmissiveBox(v, {Vec3d(2, -0.5, -0.5), Vec3d(3, 0.5, 0.5)}, openvdb::Vec3s(4, 0, 0), 100.f);
    const ImageRGB env = renderEnvmap(RenderVolume(v), Vec3d(0.0), {240, 120, MarchOptions{}});
    const EnvmapCoord right = envmapCoordinate(Vec3d(1, 0, 0), 240, 120),
                      left = envmapCoordinate(Vec3d(-1, 0, 0), 240, 120);
    EXPECT_NEAR(env.at(int(right.column), int(right.row))[0], 4.0, 1e-3);  // column 3W/4
    EXPECT_EQ(env.at(int(left.column), int(left.row))[0], 0.f);
    // Also from inside the fine level looking out, and the fine level itself holds nothing.
    EXPECT_NEAR(seen(v, Vec3d(0.5, 0, 0), Vec3d(1, 0, 0)), 4.0, 1e-3);
    EXPECT_THROW(addEmissiveBox(v, {Vec3d(1), Vec3d(0.0)}, openvdb::Vec3s(1), 1.f), InputError);
}

TEST(VolumeEdit, AddedSphereIsRoundAndInEveryLevel) {
    LightingVolume v = emptyVolume();
    addEmissiveSphere(v, Vec3d(0.5, 0, 0), 0.3, openvdb::Vec3s(0, 2, 0), 200.f);
    EXPECT_NEAR(seen(v, Vec3d(-3, 0, 0), Vec3d(1, 0, 0), 1), 2.0, 1e-3);  // through its centre
    EXPECT_EQ(seen(v, Vec3d(-3, 0.28, 0.28), Vec3d(1, 0, 0), 1),
              0.f);  // past its edge (corner of the bounding box)
    EXPECT_GT(v.levels[0].density->activeVoxelCount(), 0u);  // the coarse level too
    EXPECT_GT(v.levels[1].density->activeVoxelCount(), 0u);
}

TEST(VolumeEdit, ErasedBoxIsEmptyAndTheRestUntouched) {
    LightingVolume v = uniformVolume(2.f, openvdb::Vec3s(1.f));
    eraseBox(v, {Vec3d(-0.5, -0.5, 0), Vec3d(0.5, 0.5, 10)});
    // Along +z, starting two fine voxels inside the erased tube: nothing at all (the tube
    // runs past the volume's end at z = 4).
    EXPECT_NEAR(seen(v, Vec3d(0, 0, 0.1), Vec3d(0, 0, 1)), 0.0, 1e-6);
    // Along -z the medium is intact: 4 units of sigma 2.
    EXPECT_NEAR(seen(v, Vec3d(0.0), Vec3d(0, 0, -1)), 1 - std::exp(-2.0 * 4.0), 1e-3);
}

TEST(VolumeEdit, ExposureAndDensityScaleExactly) {
    LightingVolume v = uniformVolume(0.5f, openvdb::Vec3s(1.f, 0.5f, 0.25f));
    const float before = seen(v, Vec3d(0.0), Vec3d(1, 0, 0));
    scaleExposure(v, 3.f);
    EXPECT_NEAR(seen(v, Vec3d(0.0), Vec3d(1, 0, 0)), 3 * before, 1e-5);
    scaleDensity(v, 2.f);  // 4 units of sigma 1 now
    EXPECT_NEAR(seen(v, Vec3d(0.0), Vec3d(1, 0, 0)), 3 * (1 - std::exp(-1.0 * 4.0)), 1e-4);
}

TEST(VolumeEdit, CropKeepsOnlyTheBox) {
    LightingVolume v = uniformVolume(3.f, openvdb::Vec3s(1.f));
    cropToBox(v, {Vec3d(-2, -2, -2), Vec3d(2, 2, 2)});
    // Along +x: medium up to x = 2 only, then nothing.
    EXPECT_NEAR(seen(v, Vec3d(0.0), Vec3d(1, 0, 0)), 1 - std::exp(-3.0 * 2.0), 1e-4);
    EXPECT_FALSE(v.layout.has_value());
    EXPECT_THROW(cropToBox(v, {Vec3d(10), Vec3d(11)}), InputError);
}

}  // namespace
}  // namespace lh
