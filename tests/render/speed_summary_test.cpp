#include "render/speed_summary.h"

#include <gtest/gtest.h>

namespace lh {
namespace {

// A run with a known answer: which of ours is fastest within 1e-3, and how each of the
// paper's settings compares with our fastest at equal or lower error.
std::vector<SpeedErrorRow> knownRun() {
    return {
        {"reference-check", "step 0.025, tau<0.01", 2000.0, 1e-5, 99},  // not ours: never chosen
        {"ours-cells", "1 Gauss node/cell, bound 8", 5.0, 2e-2, 52},
        {"ours-cells", "2 Gauss nodes/cell, bound 1", 10.0, 5e-4, 75},   // the default
        {"ours-cells", "2 Gauss nodes/cell, bound 3", 8.0, 9e-4, 72},
        {"ours-steps", "step 0.5, T<0.0001, tau<0.5", 20.0, 2e-3, 57},
        {"paper-spheres", "32 spheres/level", 30.0, 5e-1, 33},
        {"paper-spheres", "128 spheres/level", 100.0, 4e-2, 51},
        {"paper-spheres", "512 spheres/level", 400.0, 1e-5, 90},         // better than all of ours
    };
}

TEST(SpeedSummary, FindsTheFastestWithinTheBoundAndTheDefault) {
    const SpeedSummary s = summarizeSpeedAgainstError(knownRun());
    ASSERT_TRUE(s.fastestWithinBound);
    EXPECT_EQ(s.fastestWithinBound->setting, "2 Gauss nodes/cell, bound 3");  // 8 ms, 9e-4
    ASSERT_TRUE(s.defaultSetting);
    EXPECT_EQ(s.defaultSetting->msPerEnvmap, 10.0);
    // A tighter bound than any of ours reaches: none.
    EXPECT_FALSE(summarizeSpeedAgainstError(knownRun(), 1e-4).fastestWithinBound);
}

TEST(SpeedSummary, ComparesEachPaperSettingWithOurFastestAtEqualOrLowerError) {
    const SpeedSummary s = summarizeSpeedAgainstError(knownRun());
    ASSERT_EQ(s.againstPaper.size(), 3u);
    // 32 spheres (0.5): every row of ours qualifies; the fastest is 1 node at 5 ms: 6x.
    ASSERT_TRUE(s.againstPaper[0].ours);
    EXPECT_EQ(s.againstPaper[0].ours->setting, "1 Gauss node/cell, bound 8");
    EXPECT_DOUBLE_EQ(s.againstPaper[0].speedup, 6.0);
    // 128 spheres (4e-2): still the 1-node row (2e-2 <= 4e-2): 20x.
    EXPECT_DOUBLE_EQ(s.againstPaper[1].speedup, 20.0);
    // 512 spheres (1e-5): none of ours is that close, and the reference check does not count.
    EXPECT_FALSE(s.againstPaper[2].ours);
    EXPECT_EQ(s.againstPaper[2].speedup, 0.0);
}

TEST(SpeedSummary, MarkdownStatesTheAnswers) {
    const std::string md = speedSummaryMarkdown(summarizeSpeedAgainstError(knownRun()));
    EXPECT_NE(md.find("ours-cells, 2 Gauss nodes/cell, bound 3: 8 ms (125 envmaps/s) at 9.00e-04"), std::string::npos) << md;
    EXPECT_NE(md.find("| 128 spheres/level | 100 | 4.00e-02 | ours-cells, 1 Gauss node/cell, bound 8 | 5 | 2.00e-02 | 20.0 |"),
              std::string::npos) << md;
    EXPECT_NE(md.find("| 512 spheres/level | 400 | 1.00e-05 | none |"), std::string::npos) << md;
}

}  // namespace
}  // namespace lh
