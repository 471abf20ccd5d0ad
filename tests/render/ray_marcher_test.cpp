#include "render/ray_marcher.h"

#include "core/errors.h"
#include "tests/support/test_volumes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh {
namespace {

// A homogeneous cube [-1, 1]^3 of 0.05 voxels: sigma and colour everywhere inside.
LightingVolume homogeneousCube(float sigma, openvdb::Vec3s color) {
    return test::volumeOf({test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), [=](const Vec3d&) {
        return MediumSample{sigma, color};
    })});
}

void expectSlab(const RenderVolume& volume, const Vec3d& origin, const Vec3d& dir, double length,
                double sigma, openvdb::Vec3s color, const MarchOptions& options) {
    const RayResult r = marchRay(volume, origin, dir, options);
    const double transmittance = std::exp(-sigma * length);
    EXPECT_NEAR(r.transmittance, transmittance, 1e-5 * transmittance + 1e-300);
    for (int c = 0; c < 3; ++c) {
        const double expected = color[c] * (1.0 - transmittance);
        EXPECT_NEAR(r.radiance[c], expected, 1e-5 * expected + 1e-12)
            << "step " << options.stepVoxels << " skip " << options.skipEmptySpace;
    }
}

TEST(RayMarcher, HomogeneousSlabIsExactForEveryStep) {
    const float sigma = 1.3f;
    const openvdb::Vec3s color(0.8f, 0.5f, 0.25f);
    const RenderVolume volume(homogeneousCube(sigma, color));
    for (double step : {0.05, 0.25, 0.5, 1.0, 3.0, 16.0})
        for (bool skip : {true, false}) {
            MarchOptions o{step, 0.0, skip};
            o.cellNodes = 0;  // fixed steps (cell quadrature: cell_quadrature_test.cpp)
            // From the centre to the +x face: L = 1.
            expectSlab(volume, Vec3d(0), Vec3d(1, 0, 0), 1.0, sigma, color, o);
            // From outside, through the whole cube along a diagonal in the xz plane.
            const Vec3d d = Vec3d(1, 0, 1).unit();
            expectSlab(volume, Vec3d(-3, 0.3, -3), d, 2.0 * std::sqrt(2.0), sigma, color, o);
        }
}

TEST(RayMarcher, TinyDensityIsLinearInLength) {
    const float sigma = 1e-12f;
    const RenderVolume volume(homogeneousCube(sigma, openvdb::Vec3s(1.f)));
    const RayResult r = marchRay(volume, Vec3d(0), Vec3d(0, 0, 1), MarchOptions{});
    EXPECT_NEAR(r.radiance[0], double(sigma) * 1.0, 1e-5 * sigma);
    EXPECT_NEAR(r.transmittance, std::exp(-double(sigma)), 1e-14);
}

TEST(RayMarcher, OpaqueMediumReturnsItsColourAndStops) {
    const RenderVolume volume(homogeneousCube(1e30f, openvdb::Vec3s(2.f, 1.f, 0.5f)));
    const RayResult r = marchRay(volume, Vec3d(0), Vec3d(0, 1, 0), MarchOptions{});
    EXPECT_NEAR(r.radiance[0], 2.0, 1e-6);
    EXPECT_NEAR(r.radiance[2], 0.5, 1e-6);
    EXPECT_EQ(r.transmittance, 0.0);
}

TEST(RayMarcher, EarlyTerminationErrorIsBoundedByThreshold) {
    const float sigma = 20.f;  // T falls to exp(-20) over the ray: termination must happen
    const openvdb::Vec3s color(1.f);
    const RenderVolume volume(homogeneousCube(sigma, color));
    const double exact = 1.0 - std::exp(-sigma * 1.0);
    for (double threshold : {1e-2, 1e-4}) {
        const RayResult r =
            marchRay(volume, Vec3d(0), Vec3d(1, 0, 0), MarchOptions{0.5, threshold, true});
        EXPECT_LE(std::abs(r.radiance[0] - exact), threshold);
        EXPECT_LT(r.transmittance, threshold);
    }
}

// What is left of a ray when it stops takes the colour where it stopped: in a medium of one
// colour that is the exact answer, however early the stop. Dropping the rest instead would
// leave the radiance short by up to the threshold (5% here), in either quadrature.
TEST(RayMarcher, AnEarlyStopCreditsWhatIsLeftWithTheColourWhereItStopped) {
    const float sigma = 20.f;
    const RenderVolume volume(homogeneousCube(sigma, openvdb::Vec3s(2.f, 1.f, 0.5f)));
    const double exact = 1.0 - std::exp(-sigma * 1.0);  // per unit of colour
    for (int nodes : {0, 2}) {
        MarchOptions o;
        o.cellNodes = nodes;
        o.minTransmittance = 0.05;
        const RayResult r = marchRay(volume, Vec3d(0), Vec3d(1, 0, 0), o);
        EXPECT_NEAR(r.radiance[0], 2.0 * exact, 1e-6) << "nodes " << nodes;
        EXPECT_NEAR(r.radiance[2], 0.5 * exact, 1e-6) << "nodes " << nodes;
        EXPECT_EQ(r.transmittance, 0.0) << "nodes " << nodes;
    }
}

TEST(RayMarcher, RayMissingTheVolumeSeesBlack) {
    const RenderVolume volume(homogeneousCube(1.f, openvdb::Vec3s(1.f)));
    const RayResult r = marchRay(volume, Vec3d(0, 5, 0), Vec3d(1, 0, 0), MarchOptions{});
    EXPECT_EQ(r.radiance[0], 0.0);
    EXPECT_EQ(r.transmittance, 1.0);
}

TEST(RayMarcher, SurfaceDistanceIsWhereTheTransmittanceMeetsItsThreshold) {
    // From the centre of a homogeneous cube, T(t) = exp(-sigma t): it falls below T* at
    // t = -ln(T*) / sigma, in the cell quadrature and in fixed steps alike.
    const float sigma = 2.f;
    const RenderVolume volume(homogeneousCube(sigma, openvdb::Vec3s(1.f)));
    for (int nodes : {0, 2})
        for (double threshold : {0.5, 0.8, 0.3}) {
            MarchOptions o;
            o.cellNodes = nodes;
            o.surfaceTransmittance = threshold;
            const RayResult r = marchRay(volume, Vec3d(0), Vec3d(1, 0, 0), o);
            EXPECT_NEAR(r.surfaceDistance, -std::log(threshold) / sigma, 1e-6)
                << "nodes " << nodes << " threshold " << threshold;
        }
    // A ray that never gets that dark has no surface.
    MarchOptions o;
    o.surfaceTransmittance = 1e-3;  // the cube's 1 unit leaves exp(-2) = 0.135
    EXPECT_TRUE(std::isinf(marchRay(volume, Vec3d(0), Vec3d(1, 0, 0), o).surfaceDistance));
}

TEST(RayMarcher, ImpossibleOptionsAreRefused) {
    EXPECT_THROW((MarchOptions{0.0, 1e-4, true}.validate()), InputError);
    EXPECT_THROW((MarchOptions{std::nan(""), 1e-4, true}.validate()), InputError);
    EXPECT_THROW((MarchOptions{0.5, 1.5, true}.validate()), InputError);
    EXPECT_NO_THROW(MarchOptions::reference().validate());
    MarchOptions fourNodes;
    fourNodes.cellNodes = 4;
    EXPECT_THROW(fourNodes.validate(), InputError);
    for (double surface : {0.0, 1.0, std::nan("")}) {
        MarchOptions o;
        o.surfaceTransmittance = surface;
        EXPECT_THROW(o.validate(), InputError) << surface;
    }
}

}  // namespace
}  // namespace lh
