// Query points for the studies and the bound search lie where the medium is empty.
#include "render/free_space.h"

#include "tests/support/test_volumes.h"

#include <gtest/gtest.h>

#include <algorithm>
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

TEST(FreeSpacePoints, AreEmpty) {
    const RenderVolume prepared(shellVolume());
    for (const Vec3d& p : freeSpacePoints(prepared, 20, 3))
        EXPECT_EQ(prepared.sampleWorld(p).sigma, 0.f);
}

}  // namespace
}  // namespace lh
