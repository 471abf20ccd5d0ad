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
    const auto row = [&](const std::string& setting) -> const SpeedErrorRow& {
        for (const SpeedErrorRow& r : rows)
            if (r.setting == setting) return r;
        ADD_FAILURE() << "no row '" << setting << "'";
        return rows.front();
    };
    std::set<std::string> settings;
    for (const SpeedErrorRow& r : rows) {
        EXPECT_TRUE(settings.insert(r.setting).second) << "row '" << r.setting << "' measured twice";
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

// The storage target read from known rows: the default bound's row is judged, on disk and in
// memory, against a tenth of the dense size, and its loss against ground truth.
TEST(MemoryTarget, JudgesTheDefaultBoundsRow) {
    MemoryErrorRow unpruned, looser, atDefault;
    unpruned.setting = "unpruned", unpruned.tau = -1, unpruned.psnrGroundTruth = 20.0;
    looser.setting = "tau 0.1", looser.tau = 0.1, looser.diskBytesHalf = 1, looser.memoryBytes = 1;
    atDefault.setting = "tau 0.0001", atDefault.tau = 1e-4;
    atDefault.diskBytesHalf = 50'000, atDefault.memoryBytes = 300'000;  // 5% and 30% of 1 MB
    atDefault.psnrGroundTruth = 19.95, atDefault.lossDb = 0.05;
    const std::vector<MemoryErrorRow> rows{unpruned, atDefault, looser};
    std::string md = memoryTargetMarkdown(rows, 1e6, 1e-4);
    EXPECT_NE(md.find("on disk (Blosc, half precision): 0.05 MB, 5.0% of dense: **met**"), std::string::npos) << md;
    EXPECT_NE(md.find("in memory (OpenVDB grids): 0.3 MB, 30.0% of dense: **not met**"), std::string::npos) << md;
    EXPECT_NE(md.find("0.050 dB lost: **met**"), std::string::npos) << md;
    // Losing more than 0.1 dB fails the target; without ground truth it is not judged.
    std::vector<MemoryErrorRow> lossy = rows;
    lossy[1].lossDb = 0.2;
    EXPECT_NE(memoryTargetMarkdown(lossy, 1e6, 1e-4).find("0.200 dB lost: **not met**"), std::string::npos);
    lossy[1].psnrGroundTruth = -1;
    EXPECT_NE(memoryTargetMarkdown(lossy, 1e6, 1e-4).find("not measured without ground truth"), std::string::npos);
    // A run without a row at the bound says so.
    EXPECT_NE(memoryTargetMarkdown(rows, 1e6, 1e-3).find("not measured: this run has no row at that bound"),
              std::string::npos);
}

}  // namespace
}  // namespace lh
