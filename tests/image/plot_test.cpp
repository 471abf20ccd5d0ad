// The plots: every point and marker lands inside the frame, in the SVG and in the picture alike.
#include "image/plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>

namespace lh {
namespace {

// x coordinates of every circle and dashed marker line in an SVG string.
std::vector<double> drawnXs(const std::string& svg) {
    std::vector<double> xs;
    const std::regex item("<circle cx='([-0-9.e]+)'|<line x1='([-0-9.e]+)'[^>]*stroke-dasharray");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), item); it != std::sregex_iterator();
         ++it)
        xs.push_back(std::stod((*it)[1].matched ? (*it)[1].str() : (*it)[2].str()));
    return xs;
}

TEST(SvgPlot, MarkersOutsideTheDataWidenTheAxis) {
    // Data between 1e5 and 1e6 bytes, a target marker at 2e4: the marker must be in the frame
    // (it used to fall off the left edge).
    PlotSeries s{"in memory", "red", {{1e5, 90, "a"}, {1e6, 100, "b"}}, true, {}};
    const std::string svg = svgPlot({"bytes", true}, {"dB", false, 10}, {s}, {{2e4, "dense / 10"}});
    const std::vector<double> xs = drawnXs(svg);
    ASSERT_EQ(xs.size(), 3u);
    for (double x : xs) {
        EXPECT_GE(x, 70.0);   // left edge of the frame
        EXPECT_LE(x, 450.0);  // right edge (640 - 190)
    }
    EXPECT_LT(xs[0], xs[1]);  // the marker (drawn before the points) is left of 1e5
}

TEST(SvgPlot, LogAxisOrdersPointsAndFloorsZero) {
    PlotSeries s{"ours", "red", {{10, 1e-3, "a"}, {100, 0.0, "zero error"}}, false, {}};
    const std::string svg = svgPlot({"ms", true}, {"rmse", true, 10, 1e-6}, {s});
    const std::vector<double> xs = drawnXs(svg);
    ASSERT_EQ(xs.size(), 2u);
    EXPECT_LT(xs[0], xs[1]);
    EXPECT_EQ(svg.find("nan"), std::string::npos);
    EXPECT_EQ(svg.find("inf"), std::string::npos);
}

// Settings worth choosing: nothing else is both faster and more accurate.
TEST(SvgPlot, LowerLeftFrontKeepsWhatNothingBeats) {
    const std::vector<PlotPoint> front = lowerLeftFront({{5, 0.1, "a"},
                                                         {2, 1.0, "b"},
                                                         {3, 2.0, "beaten by b"},
                                                         {5, 0.05, "c"},
                                                         {9, 0.07, "beaten by c"},
                                                         {10, 0.01, "d"}});
    std::vector<std::string> names;
    for (const PlotPoint& p : front) names.push_back(p.tooltip);
    EXPECT_EQ(names, (std::vector<std::string>{"b", "c", "d"}));
    // The curve is drawn as a polyline, the points as circles.
    PlotSeries s{"ours", "red", {{2, 1.0, "b"}, {3, 2.0, "x"}, {10, 0.01, "d"}}, false, {}};
    s.curve = lowerLeftFront(s.points);
    const std::string svg = svgPlot({"ms", true}, {"rmse", true}, {s});
    EXPECT_EQ(drawnXs(svg).size(), 3u);
    EXPECT_NE(svg.find("<polyline"), std::string::npos);
}

// Text is character data: "T<0.01" in a tooltip or "<" and "&" in a label must not break the
// XML (browsers draw nothing of an SVG that is not well-formed).
TEST(SvgPlot, TextIsEscaped) {
    PlotSeries s{"ours & theirs", "red", {{10, 1e-3, "step 0.5, T<0.01"}}, false, {}};
    const std::string svg =
        svgPlot({"ms <per envmap>", true}, {"rmse", true, 10, 1e-6}, {s}, {{20, "a'b"}});
    EXPECT_NE(svg.find("<title>step 0.5, T&lt;0.01</title>"), std::string::npos) << svg;
    EXPECT_NE(svg.find(">ours &amp; theirs<"), std::string::npos) << svg;
    EXPECT_NE(svg.find(">ms &lt;per envmap&gt;<"), std::string::npos) << svg;
    EXPECT_NE(svg.find(">a&apos;b<"), std::string::npos) << svg;
    // Outside tags, no '<' is followed by anything but a tag name or '/'.
    EXPECT_FALSE(std::regex_search(svg, std::regex("<[^a-z/]"))) << svg;
}

// The picture is the same layout as the SVG: each dot is drawn, in its colour, where the SVG
// puts its circle.
TEST(PlotImage, DotsLandWhereTheSvgPutsThem) {
    PlotSeries s{"ours", "red", {{10, 1e-3, "a"}, {100, 1e-5, "b"}}, false, {}};
    const PlotAxis x{"ms", true}, y{"rmse", true, 10, 1e-6};
    const std::string svg = svgPlot(x, y, {s});
    const ImageRGB image = plotImage(x, y, {s});
    ASSERT_EQ(image.width, 640);
    ASSERT_EQ(image.height, 420);
    const std::regex circle("<circle cx='([-0-9.e]+)' cy='([-0-9.e]+)'");
    int dots = 0;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle);
         it != std::sregex_iterator(); ++it, ++dots) {
        const float* p = image.at(int(std::lround(std::stod((*it)[1].str()))),
                                  int(std::lround(std::stod((*it)[2].str()))));
        EXPECT_FLOAT_EQ(p[0], 1.f);
        EXPECT_FLOAT_EQ(p[1], 0.f);
        EXPECT_FLOAT_EQ(p[2], 0.f);
    }
    EXPECT_EQ(dots, 2);
    EXPECT_FLOAT_EQ(image.at(1, 1)[0], 1.f);  // white background
}

// A linear axis without a step gets a round one (1, 2 or 5 times a power of ten) that cuts
// the data's range into at most 5 steps: 0.05 to 0.3 gets grid lines every 0.05.
TEST(PlotImage, ALinearAxisWithoutAStepRoundsTheRange) {
    PlotSeries s{"loss", "#1f77b4", {{0, 0.05, ""}, {1, 0.3, ""}}, true, {}, /*dots=*/false};
    const std::string svg = svgPlot({"iteration", false, 1}, {"", false, 0}, {s});
    EXPECT_EQ(svg.find("<circle"), std::string::npos);
    EXPECT_NE(svg.find("<polyline"), std::string::npos);
    for (const char* label : {">0.05<", ">0.1<", ">0.15<", ">0.2<", ">0.25<", ">0.3<"})
        EXPECT_NE(svg.find(label), std::string::npos) << label << " in " << svg;
    EXPECT_EQ(svg.find(">0.35<"), std::string::npos) << svg;
}

}  // namespace
}  // namespace lh
