#include "render/speed_error.h"
#include "vdb/example_volume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace lh {
namespace {

// The rows come out in the order the settings are declared, each with its own error, after
// timing in rounds (every setting once per round).
TEST(SpeedError, RoundsKeepEachRowsOwnErrorAndTime) {
    const LightingVolume volume = makeExampleVolume(2, 16);
    SpeedErrorOptions o;
    o.points = 2, o.width = 16, o.height = 8, o.repeats = 2;
    o.methods = {"ours-cells", "paper-spheres"};
    std::set<std::string> said;
    const std::vector<SpeedErrorRow> rows =
        measureSpeedAgainstError(volume, o, [&](const std::string& s) { said.insert(s); });
    ASSERT_EQ(rows.size(), 9u * 3 + 4);  // 9 bounds x 1-3 nodes, then 32-256 spheres
    EXPECT_EQ(rows.front().setting, "1 Gauss node/cell, bound 0.25");
    EXPECT_EQ(rows[26].setting, "3 Gauss nodes/cell, bound 64");
    EXPECT_EQ(rows.back().setting, "256 spheres/level");
    for (const SpeedErrorRow& r : rows) {
        EXPECT_TRUE(std::isfinite(r.msPerEnvmap) && r.msPerEnvmap > 0.0) << r.setting;
        EXPECT_TRUE(std::isfinite(r.relativeRmse)) << r.setting;
    }
    // Errors belong to their rows: the paper's spheres converge as they get more, and our
    // default (2 nodes, bound 1) beats its coarsest setting.
    EXPECT_GT(rows[27].relativeRmse, rows[30].relativeRmse);
    EXPECT_LT(rows[2 * 3 + 1].relativeRmse, rows[27].relativeRmse);
    // Both rounds ran and said so.
    EXPECT_TRUE(said.count("round 1/2: ours-cells, 2 Gauss nodes/cell, bound 1"));
    EXPECT_TRUE(said.count("round 2/2: paper-spheres, 256 spheres/level"));
}

}  // namespace
}  // namespace lh
