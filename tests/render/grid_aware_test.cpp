// The renderer follows the grids as they are: tiles, rotated and anisotropic transforms.
#include "render/ray_marcher.h"

#include "tests/support/test_volumes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh {
namespace {

constexpr float kSigma = 0.9f;
const openvdb::Vec3s kColor(0.2f, 0.6f, 1.0f);

void expectHomogeneous(const RenderVolume& volume, const Vec3d& origin, const Vec3d& dir,
                       double length) {
    const RayResult r = marchRay(volume, origin, dir, MarchOptions{0.5, 0.0, true});
    const double t = std::exp(-kSigma * length);
    EXPECT_NEAR(r.transmittance, t, 1e-5 * t);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.radiance[c], kColor[c] * (1 - t), 1e-5 * kColor[c]);
}

TEST(GridAware, TilesRenderLikeVoxels) {
    // A 128^3 block filled with active tiles (no leaf nodes at all), voxel size 0.02.
    VolumeLevel level;
    level.density = openvdb::FloatGrid::create(0.f);
    level.color = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    auto xf = openvdb::math::Transform::createLinearTransform(0.02);
    level.density->setTransform(xf);
    level.color->setTransform(xf->copy());
    const openvdb::CoordBBox box(openvdb::Coord(0), openvdb::Coord(127));
    level.density->tree().fill(box, kSigma, true);
    level.color->tree().fill(box, kColor, true);
    ASSERT_EQ(level.density->tree().leafCount(), 0u);  // really tiles
    level.domain = level.density->evalActiveVoxelBoundingBox();
    const RenderVolume volume(test::volumeOf({level}));
    // Domain faces in world: [-0.01, 2.55]. From the centre along +y: 1.28 units.
    expectHomogeneous(volume, Vec3d(1.27, 1.27, 1.27), Vec3d(0, 1, 0), 1.28);
}

TEST(GridAware, RotatedAnisotropicTransformIsFollowed) {
    // Voxels of 0.05 x 0.1 x 0.02, rotated 30 degrees about y, moved to (1, 2, 3).
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    m.preScale(Vec3d(0.05, 0.1, 0.02));
    m.postRotate(openvdb::math::Y_AXIS, M_PI / 6);
    m.postTranslate(Vec3d(1, 2, 3));
    auto xf = openvdb::math::Transform::createLinearTransform(m);
    VolumeLevel level;
    level.density = openvdb::FloatGrid::create(0.f);
    level.color = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    level.density->setTransform(xf);
    level.color->setTransform(xf->copy());
    level.domain = openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(39));
    LightingVolume v;
    v.levels.push_back(level);
    v.fillLevel(0, [](const Vec3d&) { return MediumSample{kSigma, kColor}; });
    const RenderVolume volume(v);
    // Start at the centre of the box and leave along its local x axis: 20 voxels of 0.05.
    const Vec3d centre = xf->indexToWorld(Vec3d(19.5));
    const Vec3d axisX = xf->indexToWorld(Vec3d(1, 0, 0)) - xf->indexToWorld(Vec3d(0.0));
    const Vec3d axisZ = xf->indexToWorld(Vec3d(0, 0, 1)) - xf->indexToWorld(Vec3d(0.0));
    EXPECT_NEAR(axisX.length(), 0.05, 1e-12);
    EXPECT_NEAR(axisZ.length(), 0.02, 1e-12);
    EXPECT_LT(std::abs(axisX.y()), 1e-12);
    EXPECT_GT(std::abs(axisX.z()), 0.02);  // really rotated
    // A rotated level maps directions with its full matrix, also from a shared origin.
    const RenderLevel& prepared = volume.levels[0];
    EXPECT_FALSE(prepared.axisAligned);
    const Vec3d dir = Vec3d(0.3, -0.5, 0.8).unit();
    const LevelRay shared = prepared.rayFromIndexOrigin(volume.rayOrigin(centre).index[0], dir);
    EXPECT_LT((shared.q0 - prepared.toIndex(centre)).length(), 1e-12);
    EXPECT_LT((shared.qd - prepared.worldToIndex * dir).length(), 1e-12);
    expectHomogeneous(volume, centre, axisX.unit(), 20 * 0.05);
    expectHomogeneous(volume, centre, -axisZ.unit(), 20 * 0.02);
}

}  // namespace
}  // namespace lh
