// The renderers we measure against agree with ours where the answer is known.
#include "study/baseline_renderers.h"

#include "image/envmap_layout.h"
#include "tests/support/test_volumes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh {
namespace {

TEST(BaselineRenderers, AgreeWithTheAnalyticShellAlongTheAxes) {
    const LightingVolume volume = test::boxShellVolume();
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
