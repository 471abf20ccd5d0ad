// The renderers we measure against agree with ours where the answer is known.
#include "study/baseline_renderers.h"

#include "image/envmap_layout.h"
#include "tests/support/test_volumes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh {
namespace {

// A homogeneous medium between |p|_inf = 1 and 2 (a box shell) around the query point.
LightingVolume shellVolume() {
    return test::volumeOf({test::makeLevel(0.05, Vec3d(-2), openvdb::Coord(80), [](const Vec3d& p) {
        const double m = std::max({std::abs(p.x()), std::abs(p.y()), std::abs(p.z())});
        return m > 1.0 ? MediumSample{1.5f, openvdb::Vec3s(2.f, 1.f, 0.5f)} : MediumSample{};
    })});
}

TEST(BaselineRenderers, AgreeWithTheAnalyticShellAlongTheAxes) {
    const LightingVolume volume = shellVolume();
    const RenderVolume prepared(volume);
    const ImageRGB spheres = renderEnvmapConcentricSpheres(prepared, Vec3d(0.0), 64, 32, 256);
    const ImageRGB fixed = renderEnvmapOpenVdbFixedStep(volume, Vec3d(0.0), 64, 32, 0.25);
    // Looking along +x through 1 unit of medium (column 3W/4 - 0.5, the middle rows).
    const double expected = 2.0 * (1 - std::exp(-1.5 * 1.0));
    const EnvmapCoord at = envmapCoordinate(Vec3d(1, 0, 0), 64, 32);
    // Sphere shells of 2.83/256 units and half-voxel steps: a few percent at most.
    EXPECT_NEAR(spheres.at(int(at.column), int(at.row))[0], expected, 0.03 * expected);
    EXPECT_NEAR(fixed.at(int(at.column), int(at.row))[0], expected, 0.03 * expected);
}

}  // namespace
}  // namespace lh
