// The report plots: every point and marker lands inside the frame.
#include "render/svg_plot.h"

#include <gtest/gtest.h>

#include <regex>

namespace lh {
namespace {

// x coordinates of every circle and dashed marker line in an SVG string.
std::vector<double> drawnXs(const std::string& svg) {
    std::vector<double> xs;
    const std::regex item("<circle cx='([-0-9.e]+)'|<line x1='([-0-9.e]+)'[^>]*stroke-dasharray");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), item); it != std::sregex_iterator(); ++it)
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
    const std::vector<PlotPoint> front = lowerLeftFront({{5, 0.1, "a"}, {2, 1.0, "b"}, {3, 2.0, "beaten by b"},
                                                        {5, 0.05, "c"}, {9, 0.07, "beaten by c"}, {10, 0.01, "d"}});
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
    const std::string svg = svgPlot({"ms <per envmap>", true}, {"rmse", true, 10, 1e-6}, {s}, {{20, "a'b"}});
    EXPECT_NE(svg.find("<title>step 0.5, T&lt;0.01</title>"), std::string::npos) << svg;
    EXPECT_NE(svg.find(">ours &amp; theirs<"), std::string::npos) << svg;
    EXPECT_NE(svg.find(">ms &lt;per envmap&gt;<"), std::string::npos) << svg;
    EXPECT_NE(svg.find(">a&apos;b<"), std::string::npos) << svg;
    // Outside tags, no '<' is followed by anything but a tag name or '/'.
    EXPECT_FALSE(std::regex_search(svg, std::regex("<[^a-z/]"))) << svg;
}

}  // namespace
}  // namespace lh
