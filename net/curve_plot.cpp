#include "net/curve_plot.h"

#include "image/image.h"
#include "image/image_io.h"
#include "image/plot.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lh::net {

namespace {

// One panel per series (pixels): a 720 x 170 frame, its name inside at the top left, the
// numbers of both axes in the margins; the first panel's top margin also holds the title.
constexpr double kPanelWidth = 720, kPanelHeight = 170, kLeft = 90, kRight = 20, kBottom = 50;
constexpr double kTitleTop = 28, kPanelTop = 10;

}  // namespace

void writeCurvePlot(const std::string& path, const std::string& title, const std::string& xLabel,
                    const std::vector<CurveSeries>& series) {
    // Every panel spans the x range of all series, so that iterations line up down the page.
    double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin;
    for (const auto& s : series)
        for (double x : s.x)
            if (std::isfinite(x)) xmin = std::min(xmin, x), xmax = std::max(xmax, x);
    if (!(xmax > xmin)) xmin = 0, xmax = 1;
    const PlotAxis xAxis{xLabel, false, 0, 0, xmin, xmax}, yAxis{"", false, 0};

    std::vector<ImageRGB> panels;
    for (std::size_t p = 0; p < std::max<std::size_t>(1, series.size()); ++p) {
        PlotFrame frame;
        frame.top = p == 0 ? kTitleTop : kPanelTop;
        frame.width = kLeft + kPanelWidth + kRight;
        frame.height = frame.top + kPanelHeight + kBottom;
        frame.left = kLeft, frame.right = kRight, frame.bottom = kBottom;
        frame.title = p == 0 ? title : "";
        frame.legendInside = true;
        PlotSeries curve{"", "#3f7cda", {}, /*joined=*/true, {}, /*dots=*/false};
        if (p < series.size()) {
            const CurveSeries& s = series[p];
            curve.name = s.name;
            for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
                curve.points.push_back({s.x[i], s.y[i], ""});
        }
        panels.push_back(plotImage(xAxis, yAxis, {curve}, {}, frame));
    }
    int height = 0;
    for (const ImageRGB& panel : panels) height += panel.height;
    ImageRGB page(panels.front().width, height);
    int top = 0;
    for (const ImageRGB& panel : panels) {
        std::copy(panel.pixels.begin(), panel.pixels.end(),
                  page.pixels.begin() + std::size_t(top) * page.width * 3);
        top += panel.height;
    }
    writePng(page, path);  // image_io writes through a temporary name
}

}  // namespace lh::net
