// Numerical stability on hard cases: every answer finite and within an error bound of the
// analytic one (the hard-case suite, renderer part).
#include "render/envmap.h"

#include "core/errors.h"
#include "tests/support/test_volumes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace lh {
namespace {

// Homogeneous cube [-1, 1]^3 of 0.05 voxels.
RenderVolume cube(float sigma, openvdb::Vec3s color) {
    return RenderVolume(
        test::volumeOf({test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), [=](const Vec3d&) {
            return MediumSample{sigma, color};
        })}));
}

void expectFinite(const RayResult& r) {
    for (double v : r.radiance) ASSERT_TRUE(std::isfinite(v));
    ASSERT_TRUE(std::isfinite(r.transmittance));
    ASSERT_GE(r.transmittance, 0.0);
    ASSERT_LE(r.transmittance, 1.0);
}

// Exact answer for a ray that travels `length` through a homogeneous medium.
void expectSlab(const RayResult& r, double sigma, double color, double length,
                double relative = 1e-5) {
    expectFinite(r);
    const double t = std::exp(-sigma * length);
    // The absolute floor (1e-12) admits the rounding of a ray that starts exactly on a face.
    EXPECT_NEAR(r.transmittance, t, relative * t + 1e-12);
    EXPECT_NEAR(r.radiance[0], color * (1 - t), relative * color * (1 - t) + 1e-12);
}

// Both quadratures: fixed 0.5-voxel steps and (the default) 2 Gauss nodes per lattice cell.
MarchOptions quadrature(int cellNodes) {
    MarchOptions o;
    o.cellNodes = cellNodes;
    return o;
}

const float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(HardCases, HugeAndInfiniteDensityIsOpaqueAndFinite) {
    for (int nodes : {0, 2})
        for (float sigma : {1e30f, kInf, std::numeric_limits<float>::max()}) {
            const RayResult r = marchRay(cube(sigma, openvdb::Vec3s(3.f)), Vec3d(0.0),
                                         Vec3d(1, 0, 0), quadrature(nodes));
            expectFinite(r);
            EXPECT_NEAR(r.radiance[0], 3.0, 1e-5) << sigma << ", nodes " << nodes;
            EXPECT_EQ(r.transmittance, 0.0);
        }
}

TEST(HardCases, HdrRadianceKeepsRelativePrecision) {
    const RayResult r = marchRay(cube(0.7f, openvdb::Vec3s(1e6f)), Vec3d(0.0), Vec3d(0, 0, 1),
                                 MarchOptions{0.5, 0.0, true});
    expectSlab(r, 0.7, 1e6, 1.0);
}

TEST(HardCases, NanAndInfInMemoryGridsAreCleanedNotPropagated) {
    LightingVolume v =
        test::volumeOf({test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), [](const Vec3d&) {
            return MediumSample{1.f, openvdb::Vec3s(1.f)};
        })});
    auto d = v.levels[0].density->getAccessor();
    auto c = v.levels[0].color->getAccessor();
    d.setValue(openvdb::Coord(25, 20, 20), kNaN);
    d.setValue(openvdb::Coord(30, 20, 20), -kInf);
    c.setValue(openvdb::Coord(35, 20, 20), openvdb::Vec3s(kNaN, kInf, -5.f));
    const RayResult r =
        marchRay(RenderVolume(v), Vec3d(0, 0.025, 0.025), Vec3d(1, 0, 0), MarchOptions{});
    expectFinite(r);
    // The policy (render_volume.cpp): a density that is NaN or negative is 0; a colour
    // component that is NaN or negative is 0, and +Inf is 1e15. The same volume written with
    // those values gives the same ray, to rounding.
    LightingVolume clean =
        test::volumeOf({test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), [](const Vec3d&) {
            return MediumSample{1.f, openvdb::Vec3s(1.f)};
        })});
    clean.levels[0].density->getAccessor().setValue(openvdb::Coord(25, 20, 20), 0.f);
    clean.levels[0].density->getAccessor().setValue(openvdb::Coord(30, 20, 20), 0.f);
    clean.levels[0].color->getAccessor().setValue(openvdb::Coord(35, 20, 20),
                                                  openvdb::Vec3s(0.f, 1e15f, 0.f));
    const RayResult expected =
        marchRay(RenderVolume(clean), Vec3d(0, 0.025, 0.025), Vec3d(1, 0, 0), MarchOptions{});
    EXPECT_NEAR(r.transmittance, expected.transmittance, 1e-12);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(r.radiance[c], expected.radiance[c],
                    1e-9 * std::abs(expected.radiance[c]) + 1e-12)
            << c;
    EXPECT_GT(r.radiance[1], 1e10);  // the +Inf colour, clamped, is seen
}

TEST(HardCases, PointsOnFacesEdgesCornersOutsideAndFarAway) {
    const RenderVolume volume = cube(0.5f, openvdb::Vec3s(1.f));
    // On the +x face looking in: the whole width (2) of medium ahead.
    expectSlab(marchRay(volume, Vec3d(1, 0, 0), Vec3d(-1, 0, 0), MarchOptions{}), 0.5, 1.0, 2.0);
    // On an edge and on a corner, looking along the diagonal through the cube.
    expectSlab(marchRay(volume, Vec3d(1, 1, 0), Vec3d(-1, -1, 0).unit(), MarchOptions{}), 0.5, 1.0,
               2 * std::sqrt(2.0));
    expectSlab(marchRay(volume, Vec3d(1, 1, 1), Vec3d(-1, -1, -1).unit(), MarchOptions{}), 0.5, 1.0,
               2 * std::sqrt(3.0));
    // On the face looking out: nothing.
    expectSlab(marchRay(volume, Vec3d(1, 0, 0), Vec3d(1, 0, 0), MarchOptions{}), 0.5, 1.0, 0.0);
    // Outside, and very far away, looking at the cube.
    expectSlab(marchRay(volume, Vec3d(-5, 0.3, 0.2), Vec3d(1, 0, 0), MarchOptions{}), 0.5, 1.0,
               2.0);
    expectSlab(marchRay(volume, Vec3d(-1e6, 0.3, 0.2), Vec3d(1, 0, 0), MarchOptions{}), 0.5, 1.0,
               2.0, 1e-4);
    // Envmaps at those points are finite everywhere.
    for (const Vec3d& at :
         {Vec3d(1, 1, 1), Vec3d(1, 0, 0), Vec3d(3, 3, 3), Vec3d(1e8, -1e8, 1e8)}) {
        const ImageRGB env = renderEnvmap(volume, at, {64, 32, MarchOptions{}});
        for (float x : env.pixels) ASSERT_TRUE(std::isfinite(x)) << at;
    }
}

TEST(HardCases, RaysAlongFacesAndVoxelEdges) {
    const RenderVolume volume = cube(0.5f, openvdb::Vec3s(1.f));
    // Inside the face plane y = 1 (grazing the cube) and along a voxel edge (x = 0.05 k).
    const RayResult grazing = marchRay(volume, Vec3d(-3, 1, 0), Vec3d(1, 0, 0), MarchOptions{});
    expectFinite(grazing);
    expectSlab(marchRay(volume, Vec3d(-3, 0.05, 0.1), Vec3d(1, 0, 0), MarchOptions{}), 0.5, 1.0,
               2.0);
    expectSlab(marchRay(volume, Vec3d(0.05, 0.1, -3), Vec3d(0, 0, 1), MarchOptions{}), 0.5, 1.0,
               2.0);
}

TEST(HardCases, NestedLevelBoundariesAreCrossedExactly) {
    // Two nested homogeneous levels of the same medium: the answer ignores the nesting.
    const auto field = [](const Vec3d&) { return MediumSample{0.4f, openvdb::Vec3s(2.f)}; };
    const RenderVolume volume(
        test::volumeOf({test::makeLevel(0.2, Vec3d(-4), openvdb::Coord(40), field),
                        test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), field)}));
    for (const Vec3d& origin : {Vec3d(0.0), Vec3d(1, 0, 0), Vec3d(1, 1, 1), Vec3d(-1, 0.5, 1)})
        expectSlab(marchRay(volume, origin, Vec3d(0, 0, 1), MarchOptions{}), 0.4, 2.0,
                   4.0 - origin.z());
}

TEST(HardCases, VeryThinLevel) {
    // A level one voxel thick (64 x 64 x 1): crossing it takes exactly its thickness.
    const RenderVolume volume(test::volumeOf(
        {test::makeLevel(0.01, Vec3d(-0.32, -0.32, 0), openvdb::Coord(64, 64, 1), [](const Vec3d&) {
            return MediumSample{3.f, openvdb::Vec3s(1.f)};
        })}));
    expectSlab(marchRay(volume, Vec3d(0, 0, -1), Vec3d(0, 0, 1), MarchOptions{}), 3.0, 1.0, 0.01);
    expectSlab(marchRay(volume, Vec3d(0.001, 0.002, -1), Vec3d(0.1, 0, 1).unit(), MarchOptions{}),
               3.0, 1.0, 0.01 * std::sqrt(1.01));
}

TEST(HardCases, TransmittanceUnderflowAfterLongRays) {
    // 40 units of sigma 30: exp(-1200) underflows double; without early stop the result must
    // still be the colour, finite, with transmittance exactly 0.
    const RenderVolume volume(
        test::volumeOf({test::makeLevel(1.0, Vec3d(-20), openvdb::Coord(40), [](const Vec3d&) {
            return MediumSample{30.f, openvdb::Vec3s(0.5f)};
        })}));
    for (int nodes : {0, 2}) {
        MarchOptions o = quadrature(nodes);
        o.minTransmittance = 0.0;
        o.skipEmptySpace = false;
        const RayResult r = marchRay(volume, Vec3d(-20, 0, 0), Vec3d(1, 0, 0), o);
        expectFinite(r);
        EXPECT_NEAR(r.radiance[0], 0.5, 1e-6) << "nodes " << nodes;
        EXPECT_EQ(r.transmittance, 0.0);
    }
}

TEST(HardCases, TinyAndHugeSteps) {
    const RenderVolume volume = cube(0.9f, openvdb::Vec3s(1.f));
    for (double step : {1e-4, 64.0}) {
        MarchOptions o{step, 0.0, true};
        o.cellNodes = 0;  // fixed steps
        expectSlab(marchRay(volume, Vec3d(0.0), Vec3d(0, 1, 0), o), 0.9, 1.0, 1.0);
    }
    EXPECT_THROW((MarchOptions{1e-5, 0.0, true}.validate()), InputError);
    EXPECT_THROW((MarchOptions{100.0, 0.0, true}.validate()), InputError);
}

TEST(HardCases, MoreLevelsThanTheRendererSupportsAreRefused) {
    std::vector<VolumeLevel> levels;
    for (int k = 0; k <= RenderVolume::kMaxLevels; ++k)  // 33 nested levels, 0.9x each time
        levels.push_back(test::makeLevel(std::pow(0.9, k), Vec3d(-std::pow(0.9, k)),
                                         openvdb::Coord(2), [](const Vec3d&) {
                                             return MediumSample{1.f, openvdb::Vec3s(1.f)};
                                         }));
    EXPECT_THROW(RenderVolume(test::volumeOf(levels)), InputError);
    levels.pop_back();  // 32 levels: accepted
    EXPECT_NO_THROW(RenderVolume(test::volumeOf(levels)));
}

TEST(HardCases, SmallestAndOversizedEnvmaps) {
    const RenderVolume volume = cube(0.9f, openvdb::Vec3s(1.f));
    // The two pixels of a 2x1 envmap look along -x and +x (columns W/4 and 3W/4): from the
    // centre, one unit of sigma 0.9 and colour 1 each way.
    const ImageRGB tiny = renderEnvmap(volume, Vec3d(0.0), {2, 1, MarchOptions{}});
    ASSERT_EQ(tiny.pixels.size(), 6u);
    for (float v : tiny.pixels) EXPECT_NEAR(v, 1 - std::exp(-0.9 * 1.0), 1e-5);
    EXPECT_THROW(renderEnvmap(volume, Vec3d(0.0), {1, 1, MarchOptions{}}), InputError);
    EXPECT_THROW(renderEnvmap(volume, Vec3d(0.0), {65536, 32768, MarchOptions{}}), ResourceError);
}

}  // namespace
}  // namespace lh
