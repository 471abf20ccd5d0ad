#include "study/speed_error.h"
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
    const auto row = [&](const std::string& setting) -> const SpeedErrorRow& {
        for (const SpeedErrorRow& r : rows)
            if (r.setting == setting) return r;
        ADD_FAILURE() << "no row '" << setting << "'";
        return rows.front();
    };
    std::set<std::string> settings;
    for (const SpeedErrorRow& r : rows) {
        EXPECT_TRUE(settings.insert(r.setting).second)
            << "row '" << r.setting << "' measured twice";
        EXPECT_TRUE(std::isfinite(r.msPerEnvmap) && r.msPerEnvmap > 0.0) << r.setting;
        EXPECT_TRUE(std::isfinite(r.relativeRmse) && r.relativeRmse >= 0.0) << r.setting;
    }
    // Errors belong to their rows: the paper's spheres converge as they get more, our
    // default (2 nodes, bound 1, T<1e-4) beats their coarsest setting, and stopping rays at
    // T<0.01 instead of 1e-4 loses light behind the first surfaces.
    const SpeedErrorRow& ours = row("2 Gauss nodes/cell, bound 1, T<0.0001");
    EXPECT_GT(row("32 spheres/level").relativeRmse, row("256 spheres/level").relativeRmse);
    EXPECT_LT(ours.relativeRmse, row("32 spheres/level").relativeRmse);
    EXPECT_GT(row("2 Gauss nodes/cell, bound 1, T<0.01").relativeRmse, ours.relativeRmse);
    // Both rounds ran and said so.
    EXPECT_TRUE(said.count("round 1/2: ours-cells, 2 Gauss nodes/cell, bound 1, T<0.0001"));
    EXPECT_TRUE(said.count("round 2/2: paper-spheres, 256 spheres/level"));
}

}  // namespace
}  // namespace lh
