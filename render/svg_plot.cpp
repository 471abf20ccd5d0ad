#include "render/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lh {

namespace {

// Maps data values of one axis onto [0, 1], after widening the range to round values.
struct AxisMap {
    PlotAxis axis;
    double lo = 0, hi = 1;

    AxisMap(const PlotAxis& a, double dataLo, double dataHi) : axis(a) {
        if (axis.logarithmic) {
            const double floor = axis.minimum > 0 ? axis.minimum : 1e-300;
            lo = std::pow(10, std::floor(std::log10(std::max(dataLo, floor))));
            hi = std::pow(10, std::ceil(std::log10(std::max(dataHi, floor))));
            if (hi <= lo) hi = lo * 10;
        } else {
            lo = std::floor(dataLo / axis.linearStep) * axis.linearStep;
            hi = std::ceil(dataHi / axis.linearStep) * axis.linearStep;
            if (hi <= lo) hi = lo + axis.linearStep;
        }
    }
    double value(double v) const { return axis.logarithmic ? std::log10(std::max(v, lo)) : v; }
    double unit(double v) const { return (value(v) - value(lo)) / (value(hi) - value(lo)); }
    std::vector<double> ticks() const {
        std::vector<double> t;
        if (axis.logarithmic)
            for (double v = lo; v <= hi * 1.001; v *= 10) t.push_back(v);
        else
            for (double v = lo; v <= hi + 1e-9 * axis.linearStep; v += axis.linearStep) t.push_back(v);
        return t;
    }
};

// Text as XML character data: a tooltip such as "T<0.01" must not open a tag (an SVG that
// is not well-formed XML is not drawn at all by browsers).
std::string xmlEscaped(const std::string& text) {
    std::string out;
    for (const char c : text) switch (c) {
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '&': out += "&amp;"; break;
            case '\'': out += "&apos;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    return out;
}

}  // namespace

std::vector<PlotPoint> lowerLeftFront(std::vector<PlotPoint> points) {
    std::stable_sort(points.begin(), points.end(), [](const PlotPoint& a, const PlotPoint& b) {
        return a.x < b.x || (a.x == b.x && a.y < b.y);
    });
    std::vector<PlotPoint> front;
    for (const PlotPoint& p : points)
        if (front.empty() || p.y < front.back().y) front.push_back(p);
    return front;
}

std::string svgPlot(const PlotAxis& xAxis, const PlotAxis& yAxis, const std::vector<PlotSeries>& series,
                    const std::vector<PlotMarker>& markers) {
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const auto& s : series)
        for (const auto& p : s.points)
            x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    for (const auto& m : markers) x0 = std::min(x0, m.x), x1 = std::max(x1, m.x);
    if (x0 > x1) x0 = 0, x1 = 1, y0 = 0, y1 = 1;  // nothing to plot: an empty frame
    const AxisMap mx(xAxis, x0, x1), my(yAxis, y0, y1);

    const double W = 640, H = 420, L = 70, R = 190, T = 20, B = 50;
    const auto px = [&](double x) { return L + mx.unit(x) * (W - L - R); };
    const auto py = [&](double y) { return H - B - my.unit(y) * (H - T - B); };
    std::ostringstream s;
    s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n";
    for (double x : mx.ticks())
        s << "<line x1='" << px(x) << "' y1='" << T << "' x2='" << px(x) << "' y2='" << H - B << "' stroke='#ddd'/>"
          << "<text x='" << px(x) << "' y='" << H - B + 16 << "' text-anchor='middle'>" << x << "</text>\n";
    for (double y : my.ticks())
        s << "<line x1='" << L << "' y1='" << py(y) << "' x2='" << W - R << "' y2='" << py(y) << "' stroke='#ddd'/>"
          << "<text x='" << L - 6 << "' y='" << py(y) + 4 << "' text-anchor='end'>" << y << "</text>\n";
    for (const auto& m : markers)
        s << "<line x1='" << px(m.x) << "' y1='" << T << "' x2='" << px(m.x) << "' y2='" << H - B
          << "' stroke='#888' stroke-dasharray='4 3'/><text x='" << px(m.x) + 4 << "' y='" << T + 12
          << "' fill='#555'>" << xmlEscaped(m.label) << "</text>\n";
    s << "<text x='" << (L + W - R) / 2 << "' y='" << H - 12 << "' text-anchor='middle'>" << xmlEscaped(xAxis.label) << "</text>\n"
      << "<text x='16' y='" << (T + H - B) / 2 << "' transform='rotate(-90 16 " << (T + H - B) / 2
      << ")' text-anchor='middle'>" << xmlEscaped(yAxis.label) << "</text>\n";
    const auto polyline = [&](const std::vector<PlotPoint>& points, const std::string& colour) {
        s << "<polyline fill='none' stroke='" << colour << "' points='";
        for (const auto& p : points) s << px(p.x) << "," << py(p.y) << " ";
        s << "'/>\n";
    };
    int legend = 0;
    for (const auto& sr : series) {
        if (sr.points.empty()) continue;
        if (sr.joined) polyline(sr.points, sr.colour);
        if (sr.curve.size() > 1) polyline(sr.curve, sr.colour);
        for (const auto& p : sr.points)
            s << "<circle cx='" << px(p.x) << "' cy='" << py(p.y) << "' r='4' fill='" << sr.colour << "'><title>"
              << xmlEscaped(p.tooltip) << "</title></circle>\n";
        s << "<text x='" << W - R + 12 << "' y='" << T + 20 + 18 * legend++ << "' fill='" << sr.colour << "'>"
          << xmlEscaped(sr.name) << "</text>\n";
    }
    s << "</svg>\n";
    return s.str();
}

}  // namespace lh
