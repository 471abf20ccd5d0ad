#include "net/lamp_placement.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh::net {
namespace {

TEST(LampPlacement, TheLineGivesTheMedianAngleTheShareWithin20DegAndTheOpacity) {
    const std::vector<LampPlacement> lamps = {{"a", 0, 0, 0.5, 5.0},
                                              {"a", 0, 1, 0.1, 30.0},
                                              {"b", 1, 0, 0.2, 10.0},
                                              {"b", 1, 1, 0.3, std::nan("")}};
    const std::string md = lampPlacementMarkdown(lamps);
    EXPECT_NE(md.find("4 lamp-envmap pairs"), std::string::npos) << md;
    EXPECT_NE(md.find("median opacity 0.3"), std::string::npos) << md;  // of 0.1 0.2 0.3 0.5
    EXPECT_NE(md.find("median 10.0 deg"), std::string::npos) << md;     // of 5 10 30
    EXPECT_NE(md.find("67% within 20 deg"), std::string::npos) << md;   // 2 of 3
    EXPECT_NE(md.find("1 of the pairs left out"), std::string::npos) << md;
}

TEST(LampPlacement, NoLampsNoLineAndNoHighlightsNoAngle) {
    EXPECT_EQ(lampPlacementMarkdown({}), "");
    const std::string md = lampPlacementMarkdown({{"a", 0, 0, 0.25, std::nan("")}});
    EXPECT_NE(md.find("no ground-truth envmap has a highlight"), std::string::npos) << md;
    EXPECT_EQ(md.find("within"), std::string::npos) << md;
}

TEST(LampPlacement, TheCsvHasOneRowPerLampAndEnvmap) {
    const std::string csv = lampPlacementCsv({{"scene_7", 2, 1, 0.25, 12.5}});
    EXPECT_EQ(csv,
              "example,envmap,lamp,alpha,degrees_to_nearest_highlight\n"
              "scene_7,2,1,0.25,12.5\n");
}

}  // namespace
}  // namespace lh::net
