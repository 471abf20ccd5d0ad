// Scatter and line plots, the one plot writer of the project: the study reports' SVG (speed
// against error, memory against error) and the training curves' PNG panels are both laid out
// here, then written as SVG text or drawn into an ImageRGB. One frame, grid lines at decades
// (log axes) or steps (linear axes), a legend, and a tooltip per point (SVG). No dependency
// beyond the standard library and stb_easy_font (the PNG's labels).
#pragma once

#include "image/image.h"

#include <optional>
#include <string>
#include <vector>

namespace lh {

struct PlotAxis {
    std::string label;
    bool logarithmic = false;
    double linearStep =
        10;              // grid spacing of a linear axis; <= 0: a 1-2-5 step, about 4 to 10 lines
    double minimum = 0;  // log axes: values below are drawn at this floor (> 0)
    // The axis spans at least [from, to] whatever the data (e.g. panels sharing an x range).
    std::optional<double> from{}, to{};
};

struct PlotPoint {
    double x = 0, y = 0;  // non-finite points are left out
    std::string tooltip;
};

struct PlotSeries {
    std::string name;    // in the legend (empty: none)
    std::string colour;  // CSS colour: #rgb, #rrggbb, or black, white, red, green, blue, grey
    std::vector<PlotPoint> points;
    bool joined = false;           // draw a polyline through the points in order
    std::vector<PlotPoint> curve;  // drawn as a polyline (in order) beside the points
    bool dots = true;              // draw each point as a dot
};

// The points that no other point beats on both axes (smaller x and smaller y: for time
// against error, the settings worth choosing), ordered by x. Ties in x keep the smaller y.
std::vector<PlotPoint> lowerLeftFront(std::vector<PlotPoint> points);

// A vertical dashed marker line with a label (e.g. "dense / 10").
struct PlotMarker {
    double x = 0;
    std::string label;
};

// The picture: its size and the margins around the frame (SVG user units, PNG pixels). The
// right margin holds the legend unless it goes inside the frame, at its top left; the title,
// when given, sits above the frame at its left.
struct PlotFrame {
    double width = 640, height = 420;
    double left = 70, right = 190, top = 20, bottom = 50;
    std::string title;
    bool legendInside = false;
};

// The axes span every point and marker, widened to whole decades (log) or steps (linear).
std::string svgPlot(const PlotAxis& x, const PlotAxis& y, const std::vector<PlotSeries>& series,
                    const std::vector<PlotMarker>& markers = {}, const PlotFrame& frame = {});

// The same plot drawn into a picture of frame.width x frame.height pixels (linear values,
// the CSS colours decoded from sRGB, so that writePng shows them as named), white background.
ImageRGB plotImage(const PlotAxis& x, const PlotAxis& y, const std::vector<PlotSeries>& series,
                   const std::vector<PlotMarker>& markers = {}, const PlotFrame& frame = {});

}  // namespace lh
