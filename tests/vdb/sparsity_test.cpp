// Error-bounded sparsity (vdb/sparsity.h) with known answers: what is dropped and what stays
// (sparsity_envmaps_test.cpp: that the envmaps stay within the bound).
#include "vdb/sparsity.h"

#include "core/errors.h"
#include "tests/support/test_volumes.h"
#include "tests/vdb/sparsity_volumes.h"
#include "vdb/example_volume.h"
#include "vdb/volume_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace lh {
namespace {

using test::fogVolume;
using test::linearField;
using test::twoLevelsOf;

TEST(Sparsity, BoundFollowsFromRayLengthAndBrightestColour) {
    // A 2 m cube: rays up to 2 sqrt(3) m; brightest colour 4 (only where density is).
    const LightingVolume v =
        test::volumeOf({test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), [](const Vec3d& p) {
            return MediumSample{p.x() < 0 ? 0.f : 1.f,
                                p.x() < 0 ? openvdb::Vec3s(100.f) : openvdb::Vec3s(1.f, 4.f, 2.f)};
        })});
    const SparsityBound b = sparsityBound(v, 0.03);
    EXPECT_NEAR(b.rayLength, 2 * std::sqrt(3.0), 1e-9);
    EXPECT_FLOAT_EQ(b.maxColour, 4.f);
    EXPECT_NEAR(b.fieldBound, 0.03 / (3 * 2 * std::sqrt(3.0)), 1e-12);
    EXPECT_NEAR(b.thinDensity(), b.fieldBound / 4, 1e-12);
}

TEST(Sparsity, VoxelsBelowTheBoundAreDroppedAndTheRestKept) {
    // 0.05 voxels in a 2 m cube; tau 0.1: eps = 0.1 / (3 * 3.46) = 9.6e-3 per unit, colour 1.
    // x < 0: sigma 1e-3 (dropped), x > 0: sigma 10 (kept).
    const LightingVolume v =
        test::volumeOf({test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), [](const Vec3d& p) {
            return MediumSample{p.x() < 0 ? 1e-3f : 10.f, openvdb::Vec3s(1.f)};
        })});
    SparsityOptions o;
    o.tau = 0.1;
    o.pruneTiles = false;
    SparsityStats stats;
    const LightingVolume s = sparsify(v, o, &stats);
    EXPECT_EQ(stats.activeBefore, 40u * 40 * 40);
    EXPECT_EQ(stats.thinVoxelsDropped, 20u * 40 * 40);
    EXPECT_EQ(s.levels[0].density->activeVoxelCount(), 20u * 40 * 40);
    EXPECT_EQ(s.levels[0].density->tree().getValue(openvdb::Coord(30, 5, 5)), 10.f);
    EXPECT_FALSE(s.levels[0].density->tree().isValueOn(openvdb::Coord(5, 5, 5)));
    // Bright but thin voxels stay: sigma 1e-3 but sigma * colour = 1 per unit > eps.
    const LightingVolume bright =
        test::volumeOf({test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(8), [](const Vec3d&) {
            return MediumSample{1e-3f, openvdb::Vec3s(1000.f)};
        })});
    EXPECT_EQ(activeDensityVoxels(sparsify(bright, o)), 8u * 8 * 8);
    // The input is untouched.
    EXPECT_EQ(activeDensityVoxels(v), 40u * 40 * 40);
}

// What a file says about the volume travels with it: a sparsified shell is still a shell.
TEST(Sparsity, KeepsTheCameraAndTheShellsCentre) {
    LightingVolume v = makeExampleVolume(2, 16);
    v.shellCentre = Vec3d(0.0, 0.1, 1.5);
    SparsityOptions o;
    o.tau = 0.1;
    const LightingVolume s = sparsify(v, o);
    ASSERT_TRUE(s.refCamera && s.shellCentre);
    EXPECT_EQ(s.refCamera->fx, v.refCamera->fx);
    EXPECT_EQ(*s.shellCentre, *v.shellCentre);
}

TEST(Sparsity, MemoryBreakdownAddsUpToTheGrids) {
    const LightingVolume v = fogVolume();
    const MemoryBreakdown m = memoryBreakdown(v);
    EXPECT_EQ(m.total(), v.memoryBytes());
    EXPECT_EQ(m.activeVoxels, 2u * 40 * 40 * 40);
    EXPECT_EQ(m.leafCount, 2u * 5 * 5 * 5);  // 40 = 5 leaves of 8 per axis, both levels
    EXPECT_GT(m.densityUpper, 0u);
    // Fixed tables: a Vec3s node entry takes 16 bytes against a float's 8.
    EXPECT_GT(m.colourUpper, m.densityUpper);
}

TEST(Sparsity, MaxLevelsKeepsTheCoarsest) {
    SparsityOptions o;
    o.maxLevels = 1;
    o.dropReproducedFine = false;
    const LightingVolume s = sparsify(twoLevelsOf(linearField, linearField), o);
    ASSERT_EQ(s.levels.size(), 1u);
    EXPECT_NEAR(std::cbrt(s.levels[0].voxelVolume()), 0.1, 1e-12);
}

TEST(Sparsity, LevelsFromDepthRange) {
    // s0 = 2 * 6.275 = 12.55; sides 12.55, 6.28, 3.14, 1.57: the 4th is below near = 2.09.
    EXPECT_EQ(levelsForDepthRange(2.0878, 6.275), 3);
    EXPECT_EQ(levelsForDepthRange(0.1, 100.0), 5);     // capped at maxLevels
    EXPECT_EQ(levelsForDepthRange(0.1, 100.0, 9), 9);  // s0 = 40: 40 / 2^8 = 0.156 >= 0.1
    EXPECT_EQ(levelsForDepthRange(10.0, 10.0), 2);     // 20 / 2 = 10 >= 10
    EXPECT_THROW(levelsForDepthRange(3.0, 2.0), InputError);
    EXPECT_THROW(levelsForDepthRange(0.0, 2.0), InputError);
    EXPECT_THROW(levelsForDepthRange(1.0, std::nan("")), InputError);
}

TEST(Sparsity, BadOptionsAreRejected) {
    const LightingVolume v = twoLevelsOf(linearField, linearField);
    for (double tau : {-1.0, 2.0, std::nan("")}) {
        SparsityOptions o;
        o.tau = tau;
        EXPECT_THROW(sparsify(v, o), InputError) << tau;
    }
    SparsityOptions o;
    o.maxLevels = -1;
    EXPECT_THROW(sparsify(v, o), InputError);
}

TEST(Sparsity, HalfPrecisionRoundTripIsWithinItsBound) {
    const float values[] = {1.2345f, 0.001f, 777.7f, 50000.f, 1e6f};
    const LightingVolume v = test::volumeOf(
        {test::makeLevel(0.05, Vec3d(0), openvdb::Coord(5, 1, 1), [&](const Vec3d& p) {
            const float x = values[int(p.x() / 0.05)];
            return MediumSample{x, openvdb::Vec3s(x, 0.5f * x, 2.f)};
        })});
    const std::string path =
        (std::filesystem::temp_directory_path() / "lh_sparsity_half_test.vdb").string();
    saveSparseVolume(path, v, true);
    const LightingVolume back = loadVolume(path);
    std::filesystem::remove(path);
    auto d = back.levels[0].density->getConstAccessor();
    auto c = back.levels[0].color->getConstAccessor();
    for (int i = 0; i < 5; ++i) {
        const float expected = std::min(values[i], kHalfSafeMax);  // clamped, never Inf
        const float bound = expected * std::ldexp(1.f, -11);       // half rounding, relative
        EXPECT_NEAR(d.getValue(openvdb::Coord(i, 0, 0)), expected, bound) << values[i];
        EXPECT_NEAR(c.getValue(openvdb::Coord(i, 0, 0)).x(), expected, bound) << values[i];
        EXPECT_NEAR(c.getValue(openvdb::Coord(i, 0, 0)).z(), 2.f, 2.f * std::ldexp(1.f, -11));
    }
}

}  // namespace
}  // namespace lh
