// Error-bounded sparsity (vdb/sparsity.h) as the renderer sees it: the envmaps of a sparsified
// volume stay within the bound, and the query points of the bound search in fog.
#include "vdb/sparsity.h"

#include "core/errors.h"
#include "render/envmap.h"
#include "render/free_space.h"
#include "tests/support/test_volumes.h"
#include "tests/vdb/sparsity_volumes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh {
namespace {

using test::fogVolume;
using test::linearField;
using test::twoLevelsOf;

double maxAbsDifference(const ImageRGB& a, const ImageRGB& b) {
    double d = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        d = std::max(d, std::abs(double(a.pixels[i]) - b.pixels[i]));
    return d;
}

// Fine steps: differences then come from the volumes, not from where the steps fall.
ImageRGB envmapAt(const LightingVolume& v, const Vec3d& p) {
    return renderEnvmap(RenderVolume(v), p, {32, 16, MarchOptions{0.05, 0.0, true, 0.05}});
}

TEST(Sparsity, NearlyConstantFieldBecomesTilesAndRendersWithinTheBound) {
    // sigma 0.8 with 1e-5 of ripple: leaves (exact zeros only are left out when filling),
    // which the tile pruning collapses: tolerance eps / (6 C) = 1e-3 / (3 * 5.54) / 3.6 = 1.7e-5.
    const LightingVolume v =
        test::volumeOf({test::makeLevel(0.05, Vec3d(-1.6), openvdb::Coord(64), [](const Vec3d& p) {
            const int ripple = int(std::floor(p.x() * 20) + 3 * std::floor(p.y() * 20) +
                                   7 * std::floor(p.z() * 20)) &
                               7;
            return MediumSample{0.8f + 1e-5f * ripple / 7.f, openvdb::Vec3s(0.6f, 0.4f, 0.2f)};
        })});
    ASSERT_GT(v.levels[0].density->tree().leafCount(), 0u);
    SparsityStats stats;
    const LightingVolume s = sparsify(v, SparsityOptions{1e-3}, &stats);
    EXPECT_EQ(stats.activeAfter, stats.activeBefore);  // nothing dropped ...
    // ... but stored as tiles: what is left is the trees' fixed upper nodes (~0.45 MB a grid).
    EXPECT_LT(stats.memoryAfter * 2, stats.memoryBefore);
    EXPECT_EQ(s.levels[0].density->tree().leafCount(), 0u);
    const Vec3d p(0.1, -0.2, 0.3);
    EXPECT_LE(maxAbsDifference(envmapAt(s, p), envmapAt(v, p)), 1e-3);  // tau
}

TEST(Sparsity, FinerLevelEqualToUpsampledCoarseIsDroppedAndRendersTheSame) {
    const LightingVolume v = twoLevelsOf(linearField, linearField);
    SparsityStats stats;
    const LightingVolume s = sparsify(v, SparsityOptions{}, &stats);
    ASSERT_EQ(s.levels.size(), 1u);
    EXPECT_EQ(stats.levelsDropped, 1);
    EXPECT_NEAR(std::cbrt(s.levels[0].voxelVolume()), 0.1, 1e-12);  // the coarse one stays
    for (const Vec3d& p : {Vec3d(0.1, 0.05, 0.2), Vec3d(-0.7, 0.3, -0.4)}) {
        const ImageRGB a = envmapAt(s, p), b = envmapAt(v, p);
        for (std::size_t i = 0; i < a.pixels.size(); ++i)
            EXPECT_NEAR(a.pixels[i], b.pixels[i], 1e-4 * b.pixels[i] + 1e-7);
    }
}

TEST(Sparsity, FinerLevelShrinksToWhatTheCoarserMisses) {
    // The fine level adds a bright 0.1 box at [0.2, 0.3]^3 (fine voxels 14..15 per axis).
    const auto fine = [](const Vec3d& p) {
        const bool in =
            p.x() > 0.2 && p.x() < 0.3 && p.y() > 0.2 && p.y() < 0.3 && p.z() > 0.2 && p.z() < 0.3;
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
    EXPECT_GT(maxAbsDifference(envmapAt(empty, Vec3d(0, 0, 0)), envmapAt(v, Vec3d(0, 0, 0))),
              3 * o.tau);
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

}  // namespace
}  // namespace lh
