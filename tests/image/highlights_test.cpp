#include "image/highlights.h"

#include "core/errors.h"
#include "image/envmap_layout.h"
#include "image/metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh {
namespace {

constexpr int kW = 240, kH = 120;

// A dim room (0.2 everywhere) with lamps: every pixel within `radiusDeg` of each direction
// set to radiance 30.
ImageRGB roomWithLamps(const std::vector<Vec3d>& lamps, double radiusDeg = 6.0) {
    ImageRGB image(kW, kH);
    const double cosRadius = std::cos(radiusDeg * M_PI / 180.0);
    for (int r = 0; r < kH; ++r)
        for (int c = 0; c < kW; ++c) {
            float value = 0.2f;
            for (const Vec3d& lamp : lamps)
                if (envmapPixelDirection(r, c, kW, kH).dot(lamp.unit()) >= cosRadius) value = 30.f;
            float* p = image.at(c, r);
            p[0] = p[1] = p[2] = value;
        }
    return image;
}

// The unit direction at azimuth `deg` from +z towards +x, on the horizon.
Vec3d horizon(double deg) {
    return Vec3d(std::sin(deg * M_PI / 180.0), 0.0, std::cos(deg * M_PI / 180.0));
}

TEST(Highlights, TheTruthItselfMatchesFully) {
    const ImageRGB room = roomWithLamps({horizon(90), Vec3d(0, -1, 0)});
    const HighlightMatch m = matchHighlights(room, room);
    EXPECT_DOUBLE_EQ(m.recall, 1.0);
    EXPECT_DOUBLE_EQ(m.precision, 1.0);
}

TEST(Highlights, ADimPredictionFindsNoLampAndClaimsNone) {
    const HighlightMatch m = matchHighlights(roomWithLamps({}), roomWithLamps({horizon(90)}));
    EXPECT_DOUBLE_EQ(m.recall, 0.0);
    EXPECT_TRUE(std::isnan(m.precision));  // nothing predicted to be right or wrong about
}

TEST(Highlights, ALampWhereTheRoomHasNoneIsImprecise) {
    const HighlightMatch m = matchHighlights(roomWithLamps({horizon(90)}), roomWithLamps({}));
    EXPECT_TRUE(std::isnan(m.recall));
    EXPECT_DOUBLE_EQ(m.precision, 0.0);
}

TEST(Highlights, ALampSlightlyOffCountsAndOneFarOffDoesNot) {
    const ImageRGB truth = roomWithLamps({horizon(90)});  // +x: column 3W/4
    const HighlightMatch near = matchHighlights(roomWithLamps({horizon(95)}), truth);
    EXPECT_DOUBLE_EQ(near.recall, 1.0);  // every true pixel within 5 deg of a predicted one
    EXPECT_DOUBLE_EQ(near.precision, 1.0);
    const HighlightMatch far = matchHighlights(roomWithLamps({horizon(130)}), truth);
    EXPECT_DOUBLE_EQ(far.recall, 0.0);  // discs of 6 deg, 40 deg apart: over 10 deg everywhere
    EXPECT_DOUBLE_EQ(far.precision, 0.0);
    // 20 deg apart: the discs' near edges are 8 deg apart, so part of each counts.
    const HighlightMatch part = matchHighlights(roomWithLamps({horizon(110)}), truth);
    EXPECT_GT(part.recall, 0.05);
    EXPECT_LT(part.recall, 0.95);
}

TEST(Highlights, OneOfTwoEqualLampsIsHalfTheRecall) {
    const ImageRGB truth = roomWithLamps({horizon(90), horizon(-90)});
    const HighlightMatch m = matchHighlights(roomWithLamps({horizon(90)}), truth);
    EXPECT_NEAR(m.recall, 0.5, 1e-9);  // mirror images: the same solid angle
    EXPECT_DOUBLE_EQ(m.precision, 1.0);
}

TEST(Highlights, MatchesAcrossTheSeamBehindAndOverThePole) {
    // Column 0 and column W-1 look backwards, a pixel apart across the seam.
    ImageRGB truth = roomWithLamps({}), pred = roomWithLamps({});
    truth.at(0, kH / 2)[1] = 30.f;
    pred.at(kW - 1, kH / 2)[1] = 30.f;
    EXPECT_DOUBLE_EQ(matchHighlights(pred, truth).recall, 1.0);
    // Row 0 at opposite azimuths: 1.5 deg apart through the zenith.
    ImageRGB top = roomWithLamps({}), opposite = roomWithLamps({});
    top.at(0, 0)[1] = 30.f;
    opposite.at(kW / 2, 0)[1] = 30.f;
    EXPECT_DOUBLE_EQ(matchHighlights(opposite, top).recall, 1.0);
    // With a radius of 1 deg neither matches.
    EXPECT_DOUBLE_EQ(matchHighlights(opposite, top, 1.0).recall, 0.0);
}

TEST(Highlights, CountsOnlyPixelsAboveLuminanceOne) {
    ImageRGB truth = roomWithLamps({}), pred = roomWithLamps({});
    float* t = truth.at(10, 60);
    t[0] = t[1] = t[2] = 1.01f;  // a display shows it white: a highlight
    float* p = pred.at(10, 60);
    p[0] = p[1] = p[2] = 0.99f;  // just below: not one
    EXPECT_DOUBLE_EQ(matchHighlights(pred, truth).recall, 0.0);
    p[1] = 1.5f;  // Y = 0.2126 0.99 + 0.7152 1.5 + 0.0722 0.99 > 1
    EXPECT_DOUBLE_EQ(matchHighlights(pred, truth).recall, 1.0);
}

TEST(Highlights, CompareEnvmapsReportsThem) {
    const ImageRGB truth = roomWithLamps({horizon(90), horizon(-90)});
    const EnvmapMetrics m = compareEnvmaps(roomWithLamps({horizon(90)}), truth);
    EXPECT_NEAR(m.highlightRecall, 0.5, 1e-9);
    EXPECT_DOUBLE_EQ(m.highlightPrecision, 1.0);
    EXPECT_EQ(metricColumns(m)[10], m.highlightRecall);
    EXPECT_EQ(metricColumns(m)[11], m.highlightPrecision);
    EXPECT_STREQ(kEnvmapMetricColumnNames[10], "highlight_recall");
}

TEST(Highlights, ALampsDirectionIsScoredByItsAngleToTheNearestTrueHighlight) {
    // Lamps of radius 6 deg at +x (azimuth 90) and straight up (-y).
    const ImageRGB truth = roomWithLamps({horizon(90), Vec3d(0, -1, 0)});
    // Into a lamp: the nearest pixel centre is within half a pixel's diagonal (pixels of 1.5
    // deg, so 1.06 deg).
    EXPECT_LT(degreesToNearestHighlight(truth, horizon(90)), 1.1);
    EXPECT_LT(degreesToNearestHighlight(truth, Vec3d(0, -3, 0)), 1.1);  // any length
    // 30 deg from the +x lamp's centre: its edge is 24 deg away, give or take a pixel (1.5 deg).
    EXPECT_NEAR(degreesToNearestHighlight(truth, horizon(120)), 24.0, 1.5);
    // Straight down: the lamp overhead is 174 deg away, the one at +x 84.
    EXPECT_NEAR(degreesToNearestHighlight(truth, Vec3d(0, 1, 0)), 84.0, 1.5);
    EXPECT_TRUE(std::isnan(degreesToNearestHighlight(roomWithLamps({}), horizon(0))));
    EXPECT_THROW(degreesToNearestHighlight(truth, Vec3d(0, 0, 0)), InputError);
    EXPECT_THROW(degreesToNearestHighlight(ImageRGB(0, 0), horizon(0)), InputError);
}

TEST(Highlights, RefusesDifferentSizesAndBadRadii) {
    EXPECT_THROW(matchHighlights(ImageRGB(8, 4), ImageRGB(16, 8)), InputError);
    EXPECT_THROW(matchHighlights(ImageRGB(8, 4), ImageRGB(8, 4), 0.0), InputError);
    EXPECT_THROW(matchHighlights(ImageRGB(8, 4), ImageRGB(8, 4), std::nan("")), InputError);
    EXPECT_THROW(matchHighlights(ImageRGB(8, 4), ImageRGB(8, 4), 181.0), InputError);
}

}  // namespace
}  // namespace lh
