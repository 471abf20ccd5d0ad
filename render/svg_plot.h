// Minimal SVG scatter/line plots for the benchmark reports (speed against error, memory
// against error): one frame, grid lines at decades (log axes) or steps (linear axes), a legend,
// and a tooltip per point. No dependency beyond the standard library.
#pragma once

#include <string>
#include <vector>

namespace lh {

struct PlotAxis {
    std::string label;
    bool logarithmic = false;
    double linearStep = 10;  // grid spacing of a linear axis
    double minimum = 0;      // log axes: values below are drawn at this floor (> 0)
};

struct PlotPoint {
    double x = 0, y = 0;
    std::string tooltip;
};

struct PlotSeries {
    std::string name;
    std::string colour;  // CSS colour
    std::vector<PlotPoint> points;
    bool joined = false;  // draw a polyline through the points in order
    std::vector<PlotPoint> curve;  // drawn as a polyline (in order) beside the points
};

// The points that no other point beats on both axes (smaller x and smaller y: for time
// against error, the settings worth choosing), ordered by x. Ties in x keep the smaller y.
std::vector<PlotPoint> lowerLeftFront(std::vector<PlotPoint> points);

// A vertical dashed marker line with a label (e.g. "dense / 10").
struct PlotMarker {
    double x = 0;
    std::string label;
};

// The axes span every point and marker, widened to whole decades (log) or steps (linear).
std::string svgPlot(const PlotAxis& x, const PlotAxis& y, const std::vector<PlotSeries>& series,
                    const std::vector<PlotMarker>& markers = {});

}  // namespace lh
