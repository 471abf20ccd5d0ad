// The finest-wins rule across nested levels, and continuity at level boundaries.
#include "render/envmap.h"

#include "image/envmap_layout.h"
#include "tests/support/test_volumes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh {
namespace {

MediumSample constant(float sigma, openvdb::Vec3s color) { return {sigma, color}; }

// Coarse level: [-4, 4]^3 in 0.2 voxels; fine level: [-1, 1]^3 in 0.05 voxels.
VolumeLevel coarseLevel(const std::function<MediumSample(const Vec3d&)>& f) {
    return test::makeLevel(0.2, Vec3d(-4), openvdb::Coord(40), f);
}
VolumeLevel fineLevel(const std::function<MediumSample(const Vec3d&)>& f) {
    return test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), f);
}

TEST(NestedLevels, FinestLevelDefinesTheMediumWhereLevelsOverlap) {
    const RenderVolume volume(test::volumeOf(
        {coarseLevel([](const Vec3d&) { return constant(1.f, openvdb::Vec3s(1, 0, 0)); }),
         fineLevel([](const Vec3d&) { return constant(2.f, openvdb::Vec3s(0, 1, 0)); })}));
    const RenderSample inside = volume.sampleWorld(Vec3d(0.3, -0.2, 0.1));
    EXPECT_FLOAT_EQ(inside.sigma, 2.f);
    EXPECT_FLOAT_EQ(inside.emission[1], 2.f);
    EXPECT_FLOAT_EQ(inside.emission[0], 0.f);
    const RenderSample outside = volume.sampleWorld(Vec3d(2.5, 0, 0));
    EXPECT_FLOAT_EQ(outside.sigma, 1.f);
    EXPECT_FLOAT_EQ(outside.emission[0], 1.f);

    // A ray from the centre along +x: 1 unit in the fine medium, then 3 in the coarse one.
    const RayResult r = marchRay(volume, Vec3d(0), Vec3d(1, 0, 0), MarchOptions{0.5, 0.0, true});
    const double tFine = std::exp(-2.0 * 1.0);
    // Within half a fine voxel of the face the lookup blends towards the coarse field (the
    // seam-free halo), which shifts the result by a few 1e-3.
    EXPECT_NEAR(r.radiance[1], 1.0 - tFine, 5e-3);
    EXPECT_NEAR(r.radiance[0], tFine * (1.0 - std::exp(-1.0 * 3.0)), 1e-2);
}

TEST(NestedLevels, PointInCoarseLevelOnlySeesFinerLevelsItLooksInto) {
    // Only the fine level holds something: a bright blue block at its centre.
    const RenderVolume volume(test::volumeOf(
        {coarseLevel([](const Vec3d&) { return MediumSample{}; }),
         fineLevel(test::boxField(Vec3d(-0.3), Vec3d(0.3), {50.f, openvdb::Vec3s(0, 0, 1)}))}));
    const Vec3d at(-3, 0, 0);  // inside the coarse level only, looking +x at the block
    const ImageRGB env = renderEnvmap(volume, at, {240, 120, MarchOptions{}});
    const EnvmapCoord towards = envmapCoordinate(Vec3d(1, 0, 0), 240, 120);
    EXPECT_NEAR(env.at(int(towards.column), int(towards.row))[2], 1.0, 1e-3);
    const EnvmapCoord away = envmapCoordinate(Vec3d(-1, 0, 0), 240, 120);
    EXPECT_EQ(env.at(int(away.column), int(away.row))[2], 0.f);
}

TEST(NestedLevels, AnEmptyFinerLevelClearsTheCoarseMediumItCovers) {
    // The marcher skips the parts of a level outside its occupied cells: that must not let the
    // coarse medium show through where an empty finer level covers it.
    const auto red = [](const Vec3d&) { return constant(1.f, openvdb::Vec3s(1, 0, 0)); };
    const auto nothing = [](const Vec3d&) { return MediumSample{}; };
    const RenderVolume volume(test::volumeOf({coarseLevel(red), fineLevel(nothing)}));
    // From the centre along +x: 1 unit of empty fine level, then 3 units of coarse medium
    // (plus at most half a fine voxel of blending into it at the face, the seam-free halo).
    for (const int nodes : {0, 1, 2}) {
        MarchOptions o;
        o.cellNodes = nodes;
        o.minTransmittance = 0.0;
        const RayResult r = marchRay(volume, Vec3d(0), Vec3d(1, 0, 0), o);
        EXPECT_LE(r.transmittance, std::exp(-3.0)) << nodes;
        EXPECT_GT(r.transmittance, std::exp(-3.0 - 0.05)) << nodes;
    }
    // Nothing anywhere: no level stores a brick, and every ray sees black.
    const RenderVolume empty(test::volumeOf({coarseLevel(nothing), fineLevel(nothing)}));
    EXPECT_EQ(empty.storedBricks(), 0u);
    const RayResult r = marchRay(empty, Vec3d(0.3, 0.1, 0), Vec3d(1, 1, 1).unit(), MarchOptions{});
    EXPECT_EQ(r.transmittance, 1.0);
    EXPECT_EQ(r.radiance[0], 0.0);
}

// A smooth (linear) field is reproduced exactly by trilinear interpolation, so any deviation
// near the level boundary is a seam.
MediumSample linearField(const Vec3d& p) {
    const float sigma = float(1.0 + 0.2 * p.x() + 0.1 * p.y() - 0.05 * p.z());
    // Colour chosen so that emission = sigma * colour is linear too.
    const float emissionR = float(0.5 + 0.1 * p.x());
    return {sigma, openvdb::Vec3s(emissionR / sigma, 0.3f, 0.1f)};
}

TEST(NestedLevels, NoSeamWhereASmoothFieldCrossesALevelBoundary) {
    const RenderVolume volume(test::volumeOf({coarseLevel(linearField), fineLevel(linearField)}));
    // Walk along x through the fine level's face at x = 1 (and back in at x = -1).
    double worst = 0;
    for (double x = -1.6; x <= 1.6; x += 0.001) {
        const Vec3d p(x, 0.37, -0.21);
        const RenderSample s = volume.sampleWorld(p);
        worst = std::max(worst, double(std::abs(s.sigma - linearField(p).sigma)));
        worst = std::max(worst, std::abs(s.emission[0] - (0.5 + 0.1 * x)));
    }
    EXPECT_LT(worst, 1e-5);

    // Rendered: the same field at the coarse level alone gives the same envmap.
    const RenderVolume coarseOnly(test::volumeOf({coarseLevel(linearField)}));
    const ImageRGB a =
        renderEnvmap(volume, Vec3d(0.9, 0, 0), {64, 32, MarchOptions{0.25, 0.0, true}});
    const ImageRGB b =
        renderEnvmap(coarseOnly, Vec3d(0.9, 0, 0), {64, 32, MarchOptions{0.25, 0.0, true}});
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        EXPECT_NEAR(a.pixels[i], b.pixels[i], 2e-3 * std::abs(b.pixels[i]) + 1e-6);
}

}  // namespace
}  // namespace lh
