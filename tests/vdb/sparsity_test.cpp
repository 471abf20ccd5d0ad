// Error-bounded sparsity (vdb/sparsity.h) with known answers: what is dropped, what stays, and
// that the envmaps stay within the bound.
#include "vdb/sparsity.h"

#include "core/errors.h"
#include "render/envmap.h"
#include "render/free_space.h"
#include "tests/support/test_volumes.h"
#include "vdb/volume_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace lh {
namespace {

double maxAbsDifference(const ImageRGB& a, const ImageRGB& b) {
    double d = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) d = std::max(d, std::abs(double(a.pixels[i]) - b.pixels[i]));
    return d;
}

// Fine steps: differences then come from the volumes, not from where the steps fall.
ImageRGB envmapAt(const LightingVolume& v, const Vec3d& p) {
    return renderEnvmap(RenderVolume(v), p, {32, 16, MarchOptions{0.05, 0.0, true, 0.05}});
}

TEST(Sparsity, BoundFollowsFromRayLengthAndBrightestColour) {
    // A 2 m cube: rays up to 2 sqrt(3) m; brightest colour 4 (only where density is).
    const LightingVolume v = test::volumeOf({test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), [](const Vec3d& p) {
        return MediumSample{p.x() < 0 ? 0.f : 1.f, p.x() < 0 ? openvdb::Vec3s(100.f) : openvdb::Vec3s(1.f, 4.f, 2.f)};
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
    const LightingVolume v = test::volumeOf({test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), [](const Vec3d& p) {
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
    const LightingVolume bright = test::volumeOf({test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(8), [](const Vec3d&) {
        return MediumSample{1e-3f, openvdb::Vec3s(1000.f)};
    })});
    EXPECT_EQ(activeDensityVoxels(sparsify(bright, o)), 8u * 8 * 8);
    // The input is untouched.
    EXPECT_EQ(activeDensityVoxels(v), 40u * 40 * 40);
}

TEST(Sparsity, NearlyConstantFieldBecomesTilesAndRendersWithinTheBound) {
    // sigma 0.8 with 1e-5 of ripple: leaves (exact zeros only are left out when filling),
    // which the tile pruning collapses: tolerance eps / (6 C) = 1e-3 / (3 * 5.54) / 3.6 = 1.7e-5.
    const LightingVolume v = test::volumeOf({test::makeLevel(0.05, Vec3d(-1.6), openvdb::Coord(64), [](const Vec3d& p) {
        const int ripple = int(std::floor(p.x() * 20) + 3 * std::floor(p.y() * 20) + 7 * std::floor(p.z() * 20)) & 7;
        return MediumSample{0.8f + 1e-5f * ripple / 7.f, openvdb::Vec3s(0.6f, 0.4f, 0.2f)};
    })});
    ASSERT_GT(v.levels[0].density->tree().leafCount(), 0u);
    SparsityStats stats;
    const LightingVolume s = sparsify(v, SparsityOptions{1e-3}, &stats);
    EXPECT_EQ(stats.activeAfter, stats.activeBefore);           // nothing dropped ...
    // ... but stored as tiles: what is left is the trees' fixed upper nodes (~0.45 MB a grid).
    EXPECT_LT(stats.memoryAfter * 2, stats.memoryBefore);
    EXPECT_EQ(s.levels[0].density->tree().leafCount(), 0u);
    const Vec3d p(0.1, -0.2, 0.3);
    EXPECT_LE(maxAbsDifference(envmapAt(s, p), envmapAt(v, p)), 1e-3);  // tau
}

// Two levels of a linear field: the finer one equals the coarser one upsampled.
LightingVolume twoLevelsOf(const std::function<MediumSample(const Vec3d&)>& coarse,
                           const std::function<MediumSample(const Vec3d&)>& fine) {
    return test::volumeOf({test::makeLevel(0.1, Vec3d(-1), openvdb::Coord(20), coarse),
                           test::makeLevel(0.05, Vec3d(-0.5), openvdb::Coord(20), fine)});
}

MediumSample linearField(const Vec3d& p) { return {float(2.0 + p.x()), openvdb::Vec3s(0.5f, 0.3f, 0.2f)}; }

TEST(Sparsity, FinerLevelEqualToUpsampledCoarseIsDroppedAndRendersTheSame) {
    const LightingVolume v = twoLevelsOf(linearField, linearField);
    SparsityStats stats;
    const LightingVolume s = sparsify(v, SparsityOptions{}, &stats);
    ASSERT_EQ(s.levels.size(), 1u);
    EXPECT_EQ(stats.levelsDropped, 1);
    EXPECT_NEAR(std::cbrt(s.levels[0].voxelVolume()), 0.1, 1e-12);  // the coarse one stays
    for (const Vec3d& p : {Vec3d(0.1, 0.05, 0.2), Vec3d(-0.7, 0.3, -0.4)}) {
        const ImageRGB a = envmapAt(s, p), b = envmapAt(v, p);
        for (std::size_t i = 0; i < a.pixels.size(); ++i) EXPECT_NEAR(a.pixels[i], b.pixels[i], 1e-4 * b.pixels[i] + 1e-7);
    }
}

TEST(Sparsity, FinerLevelShrinksToWhatTheCoarserMisses) {
    // The fine level adds a bright 0.1 box at [0.2, 0.3]^3 (fine voxels 14..15 per axis).
    const auto fine = [](const Vec3d& p) {
        const bool in = p.x() > 0.2 && p.x() < 0.3 && p.y() > 0.2 && p.y() < 0.3 && p.z() > 0.2 && p.z() < 0.3;
        return in ? MediumSample{50.f, openvdb::Vec3s(4.f)} : linearField(p);
    };
    const LightingVolume v = twoLevelsOf(linearField, fine);
    const LightingVolume s = sparsify(v, SparsityOptions{});
    ASSERT_EQ(s.levels.size(), 2u);
    // The differing voxels 14..15 plus one voxel of margin, inside the old 0..19 domain.
    EXPECT_EQ(s.levels[1].domain, openvdb::CoordBBox(openvdb::Coord(13), openvdb::Coord(16)));
    const Vec3d p(0.0, 0.0, -0.2);
    const ImageRGB a = envmapAt(s, p), b = envmapAt(v, p);
    EXPECT_LE(maxAbsDifference(a, b), 1e-3);
}

// Dense low-alpha fog on two nested levels, as the network predicts it: every voxel has a
// little density. Half the voxels (a hashed pattern) are very thin (sigma 1e-4), the others
// 0.05. Every voxel is "thin" for a per-voxel bound (sigma h <= 5e-3 < tau = 0.01), and
// dropping them all would darken the envmaps by far more than tau; the per-ray bound drops
// only the very thin ones and keeps every pixel within tau.
float fogDensity(const Vec3d& p, double h) {
    const auto i = [&](double x) { return uint32_t(int32_t(std::floor(x / h)) + 1000); };
    uint32_t k = i(p.x()) * 73856093u ^ i(p.y()) * 19349663u ^ i(p.z()) * 83492791u;
    k ^= k >> 13;
    k *= 0x5bd1e995u;
    k ^= k >> 15;
    return (k & 1) ? 0.05f : 1e-4f;
}

LightingVolume fogVolume() {
    return test::volumeOf(
        {test::makeLevel(0.1, Vec3d(-2), openvdb::Coord(40), [](const Vec3d& p) {
             return MediumSample{fogDensity(p, 0.1), openvdb::Vec3s(0.9f, 0.6f, 0.3f)};
         }),
         test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), [](const Vec3d& p) {
             return MediumSample{fogDensity(p, 0.05), openvdb::Vec3s(0.3f, 0.8f, 0.5f)};
         })});
}

TEST(Sparsity, FogKeepsEveryEnvmapPixelWithinTheBound) {
    const LightingVolume v = fogVolume();
    SparsityOptions o;
    o.tau = 0.01;
    SparsityStats stats;
    const LightingVolume s = sparsify(v, o, &stats);
    // eps = 0.01 / (3 * 4 sqrt 3) = 4.8e-4 per unit, C = 0.9: the 1e-4 voxels go, 0.05 stay.
    EXPECT_GT(stats.thinVoxelsDropped, 40u * 40 * 40 / 4);
    EXPECT_LT(stats.activeAfter, stats.activeBefore);
    EXPECT_EQ(s.levels.size(), 2u);  // the fine level differs from the coarse one everywhere
    for (const Vec3d& p : {Vec3d(0, 0, 0), Vec3d(0.3, -0.2, 0.5), Vec3d(-1.5, 1.2, 1.0)}) {
        const ImageRGB pruned = envmapAt(s, p), full = envmapAt(v, p);
        double brightest = 0;
        for (float x : full.pixels) brightest = std::max(brightest, double(x));
        EXPECT_GT(brightest, 3 * o.tau) << "the fog must matter for the test to mean anything";
        EXPECT_LE(maxAbsDifference(pruned, full), o.tau) << p;
    }
    // The old per-voxel rule (drop sigma h < tau) would have emptied the volume: that changes
    // the envmaps by far more than tau, which is what the per-ray bound prevents.
    LightingVolume empty = v;
    for (auto& level : empty.levels) {
        level.density = level.density->deepCopy();
        level.density->clear();
    }
    EXPECT_GT(maxAbsDifference(envmapAt(empty, Vec3d(0, 0, 0)), envmapAt(v, Vec3d(0, 0, 0))), 3 * o.tau);
}

TEST(Sparsity, QueryPointsInFogAreTheLeastDense) {
    // bench-sparsity's query points: fog has no empty space; the points come from the least
    // dense samples instead of failing, deterministically.
    const RenderVolume fog(fogVolume());
    const std::vector<Vec3d> a = freeSpacePoints(fog, 4, 7), b = freeSpacePoints(fog, 4, 7);
    ASSERT_EQ(a.size(), 4u);
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);
    for (const Vec3d& p : a) {
        EXPECT_GT(fog.sampleWorld(p).sigma, 0.f);
        EXPECT_LT(fog.sampleWorld(p).sigma, 0.0125f);  // the field averages 0.025
    }
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
    EXPECT_EQ(levelsForDepthRange(0.1, 100.0), 5);          // capped at maxLevels
    EXPECT_EQ(levelsForDepthRange(0.1, 100.0, 9), 9);       // s0 = 40: 40 / 2^8 = 0.156 >= 0.1
    EXPECT_EQ(levelsForDepthRange(10.0, 10.0), 2);          // 20 / 2 = 10 >= 10
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
    const LightingVolume v = test::volumeOf({test::makeLevel(0.05, Vec3d(0), openvdb::Coord(5, 1, 1), [&](const Vec3d& p) {
        const float x = values[int(p.x() / 0.05)];
        return MediumSample{x, openvdb::Vec3s(x, 0.5f * x, 2.f)};
    })});
    const std::string path = (std::filesystem::temp_directory_path() / "lh_sparsity_half_test.vdb").string();
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
