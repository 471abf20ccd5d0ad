// Query points for the studies and the bound search lie where the medium is empty.
#include "render/free_space.h"

#include "tests/support/test_volumes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace lh {
namespace {

TEST(FreeSpacePoints, AreEmpty) {
    const RenderVolume prepared(test::boxShellVolume());
    for (const Vec3d& p : freeSpacePoints(prepared, 20, 3))
        EXPECT_EQ(prepared.sampleWorld(p).sigma, 0.f);
}

}  // namespace
}  // namespace lh
