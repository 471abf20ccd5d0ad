#include "study/speed_error.h"
#include "core/errors.h"
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
    // default (2 nodes, bound 1, T<1e-3) beats their coarsest setting, and one node a cell
    // errs more than two.
    const SpeedErrorRow& ours = row("2 Gauss nodes/cell, bound 1, T<0.001");
    EXPECT_GT(row("32 spheres/level").relativeRmse, row("256 spheres/level").relativeRmse);
    EXPECT_LT(ours.relativeRmse, row("32 spheres/level").relativeRmse);
    EXPECT_GT(row("1 Gauss node/cell, bound 1, T<0.001").relativeRmse, ours.relativeRmse);
    // Both rounds ran and said so.
    EXPECT_TRUE(said.count("round 1/2: ours-cells, 2 Gauss nodes/cell, bound 1, T<0.001"));
    EXPECT_TRUE(said.count("round 2/2: paper-spheres, 256 spheres/level"));
}

// A finer reference is closer to its own half-step check: the reference-check row's error
// shrinks as the reference step is halved (the fixed-step march converges), and the rows say
// which step they were measured at.
TEST(SpeedError, AFinerReferenceAgreesBetterWithItsCheck) {
    const LightingVolume volume = makeExampleVolume(2, 16);
    SpeedErrorOptions o;
    o.points = 2, o.width = 16, o.height = 8, o.repeats = 1;
    o.methods = {"reference-check"};
    const std::vector<SpeedErrorRow> standard = measureSpeedAgainstError(volume, o);
    o.referenceStep = 0.025;
    const std::vector<SpeedErrorRow> finer = measureSpeedAgainstError(volume, o);
    ASSERT_EQ(standard.size(), 1u);
    ASSERT_EQ(finer.size(), 1u);
    EXPECT_EQ(standard[0].setting, "step 0.025, tau<0.01");
    EXPECT_EQ(finer[0].setting, "step 0.0125, tau<0.005");
    EXPECT_GT(standard[0].relativeRmse, 0.0);
    EXPECT_LT(finer[0].relativeRmse, 0.75 * standard[0].relativeRmse);
}

TEST(SpeedError, TheReferenceStepFollowsTheDefaultAndRefusesAbsurdSteps) {
    const MarchOptions atDefault = referenceMarchAt(0.05), reference = MarchOptions::reference();
    EXPECT_EQ(atDefault.stepVoxels, reference.stepVoxels);
    EXPECT_DOUBLE_EQ(atDefault.maxStepOpticalDepth, reference.maxStepOpticalDepth);
    EXPECT_EQ(atDefault.skipEmptySpace, reference.skipEmptySpace);
    EXPECT_EQ(atDefault.minTransmittance, reference.minTransmittance);
    EXPECT_EQ(atDefault.cellNodes, 0);
    EXPECT_DOUBLE_EQ(referenceMarchAt(0.01).maxStepOpticalDepth, 0.004);
    SpeedErrorOptions o;
    EXPECT_NO_THROW(o.validate());
    for (double bad : {0.0, 0.004, 0.06, -1.0, std::nan("")}) {
        o.referenceStep = bad;
        EXPECT_THROW(o.validate(), InputError) << bad;
    }
}

}  // namespace
}  // namespace lh
