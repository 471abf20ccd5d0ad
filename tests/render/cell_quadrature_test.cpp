// Cell quadrature (MarchOptions::cellNodes): known answers for media whose trilinear field is
// exactly a polynomial along the ray, and the nested-levels fast path of the ray partition.
#include "render/envmap.h"

#include "core/random.h"
#include "tests/support/test_volumes.h"
#include "vdb/example_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace lh {
namespace {

double linearRmse(const ImageRGB& a, const ImageRGB& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        sum += std::pow(double(a.pixels[i]) - b.pixels[i], 2);
    return std::sqrt(sum / a.pixels.size());
}

MarchOptions cells(int nodes) {
    MarchOptions o;
    o.cellNodes = nodes;
    o.minTransmittance = 0.0;
    return o;
}

// sigma = k (x + 1)(y + 1)(z + 1) on [-1, 1]^3 (0.05 voxels) with a constant colour. The field is
// trilinear, so trilinear interpolation reproduces it exactly between voxel centres, and on
// the diagonal sigma is the cubic k (s / sqrt 3)^3 of the distance s from the corner (-1, -1, -1):
// the optical depth from s0 to s0 + L is k ((s0 + L)^4 - s0^4) / (12 sqrt 3).
constexpr double kCubicK = 0.5;
RenderVolume cubicMedium() {
    return RenderVolume(
        test::volumeOf({test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), [](const Vec3d& p) {
            return MediumSample{float(kCubicK * (p.x() + 1) * (p.y() + 1) * (p.z() + 1)),
                                openvdb::Vec3s(0.7f, 0.4f, 0.2f)};
        })}));
}

TEST(CellQuadrature, TwoAndThreeNodesIntegrateACubicDensityExactly) {
    const RenderVolume volume = cubicMedium();
    // The ray starts at the last voxel centre (0.975, 0.975, 0.975) and runs down the diagonal
    // to the corner (-1, -1, -1): first over the polynomial (to the first voxel centre, at
    // s0 from the corner), then over s0 of the halo, where the edge voxel is repeated
    // (constant sigma = sigma at the first centre).
    const double s0 = 0.025 * std::sqrt(3.0);
    const double length = 1.95 * std::sqrt(3.0);
    const Vec3d dir = Vec3d(-1, -1, -1).unit();
    const double tauPolynomial =
        kCubicK * (std::pow(s0 + length, 4) - std::pow(s0, 4)) / (12 * std::sqrt(3.0));
    const double tauHalo = kCubicK * std::pow(0.025, 3) * s0;
    const double expected = std::exp(-(tauPolynomial + tauHalo));  // ~0.04
    double error[4] = {};
    for (int nodes : {1, 2, 3}) {
        const RayResult r = marchRay(volume, Vec3d(0.975), dir, cells(nodes));
        error[nodes] = std::abs(r.transmittance - expected) / expected;
        if (nodes == 1) continue;
        EXPECT_LT(error[nodes], 1e-5) << nodes << " nodes";
        // Constant colour: the radiance is the colour times the opacity.
        EXPECT_NEAR(r.radiance[0], 0.7 * (1.0 - expected), 1e-5);
    }
    // The test tells the rules apart: one node (the midpoint) is not exact for a cubic.
    EXPECT_GT(error[1], 10 * std::max(error[2], 1e-9));
}

TEST(CellQuadrature, HomogeneousSlabIsExactForEveryRule) {
    const float sigma = 1.3f;
    const RenderVolume volume(
        test::volumeOf({test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), [=](const Vec3d&) {
            return MediumSample{sigma, openvdb::Vec3s(0.8f, 0.5f, 0.25f)};
        })}));
    for (int nodes : {1, 2, 3}) {
        for (const Vec3d& dir : {Vec3d(1, 0, 0), Vec3d(1, 0, 1).unit(), Vec3d(1, 2, 3).unit()}) {
            const RayResult r = marchRay(volume, Vec3d(0), dir, cells(nodes));
            double length = 1e30;  // from the centre to the cube's surface
            for (int a = 0; a < 3; ++a)
                if (dir[a] != 0) length = std::min(length, 1.0 / std::abs(dir[a]));
            const double t = std::exp(-sigma * length);
            EXPECT_NEAR(r.transmittance, t, 1e-5 * t) << nodes << " nodes";
            EXPECT_NEAR(r.radiance[0], 0.8 * (1 - t), 1e-5 * 0.8 * (1 - t));
        }
    }
}

TEST(CellQuadrature, OpaqueWallGivesItsColourAndHalvingIsBounded) {
    // A wall of 1e6 per unit (optical depth 5e4 per voxel) at x > 0.5: every cell piece that
    // enters it is halved until its parts are thin; the ray must still return the wall colour.
    const RenderVolume volume(test::volumeOf(
        {test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40),
                         test::boxField(Vec3d(0.5, -2, -2), Vec3d(2, 2, 2),
                                        MediumSample{1e6f, openvdb::Vec3s(0.9f, 0.6f, 0.3f)}))}));
    const RayResult r = marchRay(volume, Vec3d(0, 0.01, 0.02), Vec3d(1, 0, 0), cells(2));
    EXPECT_NEAR(r.radiance[0], 0.9, 1e-3);
    EXPECT_NEAR(r.radiance[2], 0.3, 1e-3);
    EXPECT_LT(r.transmittance, 1e-6);
    // Where the ray meets the wall: trilinear density rises over the last cell before x = 0.5.
    EXPECT_GT(r.surfaceDistance, 0.45);
    EXPECT_LT(r.surfaceDistance, 0.5);
}

TEST(CellQuadrature, CloserToTheReferenceThanFixedStepsOnTheExampleRoom) {
    const RenderVolume volume(makeExampleVolume(5, 32));
    double errorCells = 0, errorSteps = 0;
    for (const Vec3d& at : {Vec3d(0, 0, 2), Vec3d(0.2, 0.1, 0.45)}) {
        const ImageRGB reference = renderEnvmap(volume, at, {64, 32, MarchOptions::reference()});
        MarchOptions steps;  // the fixed-step marcher at its usual step
        steps.cellNodes = 0;
        errorCells += linearRmse(renderEnvmap(volume, at, {64, 32, cells(2)}), reference);
        errorSteps += linearRmse(renderEnvmap(volume, at, {64, 32, steps}), reference);
    }
    EXPECT_LT(errorCells, 0.5 * errorSteps) << "cells " << errorCells << " steps " << errorSteps;
}

double meanOf(const ImageRGB& image) {
    double sum = 0;
    for (float v : image.pixels) sum += v;
    return sum / image.pixels.size();
}

TEST(CellQuadrature, DefaultsKeepTheEnvmapErrorBelowAThousandthOfTheMeanRadiance) {
    // The halving bound is weighed by brightness in units of the scene's typical radiance, so
    // that the error of an envmap stays small relative to its mean radiance: the example room's
    // lamps and window are many times brighter than its walls. The measure: RMSE over
    // a set of envmaps relative to their mean radiance, on a 5 x 64^3 volume.
    const RenderVolume volume(makeExampleVolume(5, 64));
    double squared = 0, mean = 0;
    for (const Vec3d& at : {Vec3d(0, 0, 2), Vec3d(0.2, 0.1, 0.45), Vec3d(-1, 0.5, 4)}) {
        const ImageRGB reference = renderEnvmap(volume, at, {64, 32, MarchOptions::reference()});
        squared +=
            std::pow(linearRmse(renderEnvmap(volume, at, {64, 32, MarchOptions{}}), reference), 2);
        mean += meanOf(reference);
    }
    EXPECT_LT(std::sqrt(squared / 3) / (mean / 3), 1e-3);
}

TEST(RenderVolume, TypicalRadianceIsTheMedianSurfaceColour) {
    // Walls of colour (0.5, 0.2, 0.1) and a small lamp of 100: the lamp does not move the median.
    const auto scene = [](const openvdb::Vec3s& wallColour) {
        return test::volumeOf(
            {test::makeLevel(0.1, Vec3d(-1), openvdb::Coord(20), [=](const Vec3d& p) {
                if (p.x() > 0.5 && std::abs(p.y()) < 0.15 && std::abs(p.z()) < 0.15)
                    return MediumSample{50.f, openvdb::Vec3s(100.f)};
                if (p.x() > 0.5 || p.y() < -0.5) return MediumSample{50.f, wallColour};
                return MediumSample{0.f, openvdb::Vec3s(0.f)};
            })});
    };
    EXPECT_NEAR(RenderVolume(scene(openvdb::Vec3s(0.5f, 0.2f, 0.1f))).typicalRadiance(), 0.5, 1e-6);
    // Black walls: the median is 0, and the mean keeps the lamp refined.
    const double blackWalls = RenderVolume(scene(openvdb::Vec3s(0.f))).typicalRadiance();
    EXPECT_GT(blackWalls, 0.0);
    EXPECT_LT(blackWalls, 100.0);
    // No density anywhere: nothing to refine.
    EXPECT_EQ(RenderVolume(
                  test::volumeOf({test::makeLevel(0.1, Vec3d(-1), openvdb::Coord(20),
                                                  [](const Vec3d&) {
                                                      return MediumSample{0.f, openvdb::Vec3s(1.f)};
                                                  })}))
                  .typicalRadiance(),
              0.0);
}

TEST(RenderVolume, CellBoxHoldsExactlyTheCellsAroundTheDensity) {
    // 14^3 voxels of 0.1 with density in voxel (5, 5, 5) only. Lattice point = voxel + 1
    // (one halo point), so the point is (6, 6, 6) of brick (0, 0, 0), a corner of cells 5 and 6.
    const auto oneVoxel = [](const Vec3d& p) {
        const bool in = std::abs(p.x() - 0.55) < 0.01 && std::abs(p.y() - 0.55) < 0.01 &&
                        std::abs(p.z() - 0.55) < 0.01;
        return MediumSample{in ? 4.f : 0.f, openvdb::Vec3s(1.f)};
    };
    const RenderVolume volume(
        test::volumeOf({test::makeLevel(0.1, Vec3d(0), openvdb::Coord(14), oneVoxel)}));
    const RenderLevel& level = volume.levels[0];
    ASSERT_EQ(volume.storedBricks(), 1u);
    const RenderLevel::CellBox& box = level.cellBox(level.brickIndex(0, 0, 0));
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(box.lo[a], 5);
        EXPECT_EQ(box.hi[a], 7);
    }
    // The level's occupied box is the same box, in lattice coordinates.
    EXPECT_EQ(level.occupiedLo, Vec3d(5));
    EXPECT_EQ(level.occupiedHi, Vec3d(7));
    // The marcher walks only inside the box: rays through the voxel see its density, rays
    // through the brick beside it see nothing, under every quadrature.
    for (const int nodes : {1, 2, 3}) {
        MarchOptions o = cells(nodes);
        const RayResult through = marchRay(volume, Vec3d(0.55, 0.55, -1), Vec3d(0, 0, 1), o);
        // sigma is the tent 4 (1 - |z - 0.55| / 0.1) over 0.2 units: optical depth 0.4.
        EXPECT_NEAR(through.transmittance, std::exp(-0.4), 1e-6) << nodes;
        const RayResult diagonal = marchRay(volume, Vec3d(-1, -1, -1), Vec3d(1, 1, 1).unit(), o);
        EXPECT_LT(diagonal.transmittance, 1.0) << nodes;
        const RayResult beside = marchRay(volume, Vec3d(0.25, 0.55, -1), Vec3d(0, 0, 1), o);
        EXPECT_EQ(beside.transmittance, 1.0) << nodes;
    }
}

TEST(RayPartition, NestedFastPathMatchesTheGeneralSubtraction) {
    const RenderVolume volume(makeExampleVolume(5, 32));
    ASSERT_TRUE(volume.nestedLevels());
    for (const RenderLevel& level : volume.levels) EXPECT_TRUE(level.axisAligned);
    Random rng(7);
    Piece fast[RenderVolume::kMaxPieces], general[RenderVolume::kMaxPieces];
    for (int i = 0; i < 2000; ++i) {
        // Origins inside and outside every level, any direction.
        const double spread = i % 2 ? 1.0 : 20.0;
        const Vec3d origin(rng.uniform(-spread, spread), rng.uniform(-spread, spread),
                           rng.uniform(-spread, spread) + 2);
        Vec3d dir = Vec3d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)).unit();
        if (i % 5 == 0) dir[i % 3] = 0.0, dir = dir.unit();  // parallel to two faces: 0 x inf
        if (i % 7 == 0) dir = Vec3d(0, 0, 0), dir[i % 3] = i % 2 ? 1.0 : -1.0;  // along an axis
        // The fast path's slab tests run in scene units, the general one's in each level's
        // index units: where two levels share a face, rounding may leave a piece 1e-15 long
        // in one of them. Such pieces hold no medium worth a sample; they are dropped here.
        const auto withoutSlivers = [](Piece* pieces, int count) {
            return int(std::remove_if(pieces, pieces + count,
                                      [](const Piece& p) { return p.t1 - p.t0 < 1e-12; }) -
                       pieces);
        };
        const int n = withoutSlivers(fast, volume.partitionRay(origin, dir, fast));
        ASSERT_EQ(n, withoutSlivers(general, volume.partitionRayGeneral(origin, dir, general)))
            << i;
        // The three-product direction map of axis-aligned levels is the full matrix's.
        const RenderLevel& finest = volume.levels.back();
        EXPECT_LT(
            (finest.rayFromIndexOrigin(finest.toIndex(origin), dir).qd - finest.worldToIndex * dir)
                .length(),
            1e-12);
        for (int p = 0; p < n; ++p) {
            EXPECT_EQ(fast[p].level, general[p].level);
            EXPECT_NEAR(fast[p].t0, general[p].t0, 1e-9);
            EXPECT_NEAR(fast[p].t1, general[p].t1, 1e-9);
        }
    }
}

TEST(RayPartition, OverlappingLevelsAreNotNestedAndFinestStillWins) {
    // Coarse [-4, 2]^3, fine [1, 3]^3: the fine level pokes out of the coarse one.
    const auto medium = [](const Vec3d&) { return MediumSample{1.f, openvdb::Vec3s(1.f)}; };
    const RenderVolume volume(
        test::volumeOf({test::makeLevel(0.2, Vec3d(-4), openvdb::Coord(30), medium),
                        test::makeLevel(0.1, Vec3d(1), openvdb::Coord(20), medium)}));
    EXPECT_FALSE(volume.nestedLevels());
    Piece pieces[RenderVolume::kMaxPieces];
    // Along +x at y = z = 1.5: coarse from x = -4 (t = 1), fine from x = 1 (t = 6) to 3 (t = 8).
    const int n = volume.partitionRay(Vec3d(-5, 1.5, 1.5), Vec3d(1, 0, 0), pieces);
    ASSERT_EQ(n, 2);
    EXPECT_EQ(pieces[0].level, 0);
    EXPECT_NEAR(pieces[0].t0, 1.0, 1e-9);
    EXPECT_NEAR(pieces[0].t1, 6.0, 1e-9);
    EXPECT_EQ(pieces[1].level, 1);
    EXPECT_NEAR(pieces[1].t0, 6.0, 1e-9);
    EXPECT_NEAR(pieces[1].t1, 8.0, 1e-9);
}

}  // namespace
}  // namespace lh
