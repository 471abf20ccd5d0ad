#include "image/plot.h"

#include "image/image_io.h"

#include <stb/stb_easy_font.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <utility>

namespace lh {

namespace {

// A linear axis's grid step when none is given: 1, 2 or 5 times a power of ten, the smallest
// that cuts `range` into at most 5 steps (so about 4 to 10 grid lines after rounding out);
// `magnitude` is a value of the data, the scale of a flat range.
double niceStep(double range, double magnitude) {
    if (!(range > 0))
        range = magnitude != 0 ? std::abs(magnitude) : 1.0;  // flat data: a step at its scale
    const double raw = range / 5, decade = std::pow(10, std::floor(std::log10(raw)));
    for (const double m : {1.0, 2.0, 5.0})
        if (m * decade >= raw) return m * decade;
    return 10 * decade;
}

// Maps data values of one axis onto [0, 1], after widening the range to round values.
struct AxisMap {
    PlotAxis axis;
    double lo = 0, hi = 1, step = 10;

    AxisMap(const PlotAxis& a, double dataLo, double dataHi) : axis(a) {
        if (axis.from) dataLo = std::min(dataLo, *axis.from), dataHi = std::max(dataHi, *axis.from);
        if (axis.to) dataLo = std::min(dataLo, *axis.to), dataHi = std::max(dataHi, *axis.to);
        if (axis.logarithmic) {
            const double floor = axis.minimum > 0 ? axis.minimum : 1e-300;
            lo = std::pow(10, std::floor(std::log10(std::max(dataLo, floor))));
            hi = std::pow(10, std::ceil(std::log10(std::max(dataHi, floor))));
            if (hi <= lo) hi = lo * 10;
        } else {
            step = axis.linearStep > 0 ? axis.linearStep : niceStep(dataHi - dataLo, dataHi);
            lo = std::floor(dataLo / step) * step;
            hi = std::ceil(dataHi / step) * step;
            if (hi <= lo) hi = lo + step;
        }
    }
    double value(double v) const { return axis.logarithmic ? std::log10(std::max(v, lo)) : v; }
    double unit(double v) const { return (value(v) - value(lo)) / (value(hi) - value(lo)); }
    std::vector<double> ticks() const {
        std::vector<double> t;
        if (axis.logarithmic)
            for (double v = lo; v <= hi * 1.001; v *= 10) t.push_back(v);
        else
            for (double v = lo; v <= hi + 1e-9 * step; v += step) t.push_back(v);
        return t;
    }
};

// Text as XML character data: a tooltip such as "T<0.01" must not open a tag (an SVG that
// is not well-formed XML is not drawn at all by browsers).
std::string xmlEscaped(const std::string& text) {
    std::string out;
    for (const char c : text) switch (c) {
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '&':
                out += "&amp;";
                break;
            case '\'':
                out += "&apos;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    return out;
}

std::string numberText(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

enum class Anchor { start, middle, end };
using Polyline = std::vector<std::pair<double, double>>;

// What a plot is drawn on: SVG text or a picture. Coordinates are the frame's (y down); text
// sits on its baseline at (x, y), vertical text reads upwards; an empty colour is black.
class Canvas {
public:
    virtual ~Canvas() = default;
    virtual void line(double x0, double y0, double x1, double y1, const std::string& colour,
                      bool dashed) = 0;
    virtual void polyline(const Polyline& points, const std::string& colour) = 0;
    virtual void dot(double x, double y, const std::string& colour, const std::string& tooltip) = 0;
    virtual void text(double x, double y, const std::string& text, Anchor anchor,
                      const std::string& colour, bool vertical = false) = 0;
};

class SvgCanvas : public Canvas {
public:
    explicit SvgCanvas(std::ostringstream& out) : s_(out) {}
    void line(double x0, double y0, double x1, double y1, const std::string& colour,
              bool dashed) override {
        s_ << "<line x1='" << x0 << "' y1='" << y0 << "' x2='" << x1 << "' y2='" << y1
           << "' stroke='" << colour << "'" << (dashed ? " stroke-dasharray='4 3'" : "") << "/>\n";
    }
    void polyline(const Polyline& points, const std::string& colour) override {
        s_ << "<polyline fill='none' stroke='" << colour << "' points='";
        for (const auto& [x, y] : points) s_ << x << "," << y << " ";
        s_ << "'/>\n";
    }
    void dot(double x, double y, const std::string& colour, const std::string& tooltip) override {
        s_ << "<circle cx='" << x << "' cy='" << y << "' r='4' fill='" << colour << "'><title>"
           << xmlEscaped(tooltip) << "</title></circle>\n";
    }
    void text(double x, double y, const std::string& text, Anchor anchor, const std::string& colour,
              bool vertical) override {
        s_ << "<text x='" << x << "' y='" << y << "'";
        if (vertical) s_ << " transform='rotate(-90 " << x << " " << y << ")'";
        if (anchor != Anchor::start)
            s_ << " text-anchor='" << (anchor == Anchor::middle ? "middle" : "end") << "'";
        if (!colour.empty()) s_ << " fill='" << colour << "'";
        s_ << ">" << xmlEscaped(text) << "</text>\n";
    }

private:
    std::ostringstream& s_;
};

// stb_easy_font's glyphs stand 7 pixels above the baseline; doubled they read about as large
// as the SVG's 12-pixel font.
constexpr int kTextScale = 2, kGlyphAscent = 7;

class RasterCanvas : public Canvas {
public:
    RasterCanvas(int width, int height) : image_(width, height) {
        std::fill(image_.pixels.begin(), image_.pixels.end(), 1.f);
    }
    ImageRGB& image() { return image_; }

    void line(double x0, double y0, double x1, double y1, const std::string& colour,
              bool dashed) override {
        stroke(x0, y0, x1, y1, linearColour(colour), 1, dashed);
    }
    void polyline(const Polyline& points, const std::string& colour) override {
        const auto c = linearColour(colour);
        for (std::size_t i = 1; i < points.size(); ++i)
            stroke(points[i - 1].first, points[i - 1].second, points[i].first, points[i].second, c,
                   2, false);
    }
    void dot(double x, double y, const std::string& colour, const std::string&) override {
        const auto c = linearColour(colour);
        for (int dy = -4; dy <= 4; ++dy)
            for (int dx = -4; dx <= 4; ++dx)
                if (dx * dx + dy * dy <= 16)
                    put(int(std::lround(x)) + dx, int(std::lround(y)) + dy, c);
    }
    void text(double x, double y, const std::string& text, Anchor anchor, const std::string& colour,
              bool vertical) override {
        static char buffer[99999];  // stb_easy_font's vertex buffer: 270 bytes per character
        char* chars = const_cast<char*>(text.c_str());
        const int quads = stb_easy_font_print(0, 0, chars, nullptr, buffer, sizeof(buffer));
        const double width = stb_easy_font_width(chars) * kTextScale;
        const double along = anchor == Anchor::start    ? 0
                             : anchor == Anchor::middle ? -width / 2
                                                        : -width;
        const auto c = linearColour(colour);
        for (int q = 0; q < quads; ++q) {
            // Each quad is an axis-aligned rectangle: its first and third vertices are corners.
            const float* v0 = reinterpret_cast<const float*>(buffer + q * 64);
            const float* v2 = reinterpret_cast<const float*>(buffer + q * 64 + 32);
            const double a0 = along + v0[0] * kTextScale,
                         a1 = along + v2[0] * kTextScale;  // along the text
            const double d0 = (v0[1] - kGlyphAscent) * kTextScale,
                         d1 = (v2[1] - kGlyphAscent) * kTextScale;
            if (vertical)  // rotated by -90 degrees: along the text is up, below the baseline is
                           // right
                fill(x + d0, y - a1, x + d1, y - a0, c);
            else
                fill(x + a0, y + d0, x + a1, y + d1, c);
        }
    }

private:
    using Rgb = std::array<float, 3>;

    // CSS colours as the plots use them: #rgb, #rrggbb and a few names (anything else: black).
    static Rgb linearColour(const std::string& css) {
        Rgb srgb{0, 0, 0};
        if (!css.empty() && css[0] == '#' && (css.size() == 4 || css.size() == 7)) {
            const bool shortForm = css.size() == 4;
            for (int c = 0; c < 3; ++c) {
                const std::string hex =
                    shortForm ? std::string(2, css[1 + c]) : css.substr(1 + 2 * c, 2);
                srgb[c] = std::strtol(hex.c_str(), nullptr, 16) / 255.f;
            }
        } else if (css == "white")
            srgb = {1, 1, 1};
        else if (css == "red")
            srgb = {1, 0, 0};
        else if (css == "green")
            srgb = {0, 128 / 255.f, 0};
        else if (css == "blue")
            srgb = {0, 0, 1};
        else if (css == "grey" || css == "gray")
            srgb = {128 / 255.f, 128 / 255.f, 128 / 255.f};
        return {srgbDecode(srgb[0]), srgbDecode(srgb[1]), srgbDecode(srgb[2])};
    }

    void put(int x, int y, const Rgb& c) {
        if (x >= 0 && y >= 0 && x < image_.width && y < image_.height)
            std::copy(c.begin(), c.end(), image_.at(x, y));
    }
    void fill(double x0, double y0, double x1, double y1, const Rgb& c) {
        for (int y = int(std::lround(y0)); y < int(std::lround(y1)); ++y)
            for (int x = int(std::lround(x0)); x < int(std::lround(x1)); ++x) put(x, y, c);
    }
    // A line of `thickness` pixels, one stamp per pixel of length; dashed as the SVG's
    // stroke-dasharray '4 3' (4 pixels drawn, 3 left out).
    void stroke(double x0, double y0, double x1, double y1, const Rgb& c, int thickness,
                bool dashed) {
        const int steps = int(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
        for (int s = 0; s <= steps; ++s) {
            if (dashed && s % 7 >= 4) continue;
            const double t = double(s) / steps;
            const int x = int(std::lround(x0 + (x1 - x0) * t)),
                      y = int(std::lround(y0 + (y1 - y0) * t));
            for (int dy = 0; dy < thickness; ++dy)
                for (int dx = 0; dx < thickness; ++dx) put(x + dx, y + dy, c);
        }
    }

    ImageRGB image_;
};

// The layout, the same on every canvas.
void drawPlot(Canvas& canvas, const PlotAxis& xAxis, const PlotAxis& yAxis,
              const std::vector<PlotSeries>& series, const std::vector<PlotMarker>& markers,
              const PlotFrame& frame) {
    const auto finite = [](const PlotPoint& p) { return std::isfinite(p.x) && std::isfinite(p.y); };
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const auto& s : series)
        for (const auto& p : s.points)
            if (finite(p))
                x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y),
                y1 = std::max(y1, p.y);
    for (const auto& m : markers) x0 = std::min(x0, m.x), x1 = std::max(x1, m.x);
    if (x0 > x1) x0 = 0, x1 = 1;  // nothing to plot: an empty frame
    if (y0 > y1) y0 = 0, y1 = 1;
    const AxisMap mx(xAxis, x0, x1), my(yAxis, y0, y1);

    const double W = frame.width, H = frame.height, L = frame.left, R = frame.right, T = frame.top,
                 B = frame.bottom;
    const auto px = [&](double x) { return L + mx.unit(x) * (W - L - R); };
    const auto py = [&](double y) { return H - B - my.unit(y) * (H - T - B); };
    const auto path = [&](const std::vector<PlotPoint>& points) {
        Polyline line;
        for (const auto& p : points)
            if (finite(p)) line.emplace_back(px(p.x), py(p.y));
        return line;
    };
    for (double x : mx.ticks()) {
        canvas.line(px(x), T, px(x), H - B, "#ddd", false);
        canvas.text(px(x), H - B + 16, numberText(x), Anchor::middle, "");
    }
    for (double y : my.ticks()) {
        canvas.line(L, py(y), W - R, py(y), "#ddd", false);
        canvas.text(L - 6, py(y) + 4, numberText(y), Anchor::end, "");
    }
    for (const auto& m : markers) {
        canvas.line(px(m.x), T, px(m.x), H - B, "#888", true);
        canvas.text(px(m.x) + 4, T + 12, m.label, Anchor::start, "#555");
    }
    canvas.text((L + W - R) / 2, H - 12, xAxis.label, Anchor::middle, "");
    canvas.text(16, (T + H - B) / 2, yAxis.label, Anchor::middle, "", /*vertical=*/true);
    if (!frame.title.empty()) canvas.text(L, T - 6, frame.title, Anchor::start, "");
    int legend = 0;
    for (const auto& sr : series) {
        if (sr.points.empty()) continue;
        if (sr.joined) canvas.polyline(path(sr.points), sr.colour);
        if (sr.curve.size() > 1) canvas.polyline(path(sr.curve), sr.colour);
        if (sr.dots)
            for (const auto& p : sr.points)
                if (finite(p)) canvas.dot(px(p.x), py(p.y), sr.colour, p.tooltip);
        if (sr.name.empty()) continue;
        if (frame.legendInside)
            canvas.text(L + 8, T + 20 + 18 * legend++, sr.name, Anchor::start, sr.colour);
        else
            canvas.text(W - R + 12, T + 20 + 18 * legend++, sr.name, Anchor::start, sr.colour);
    }
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

std::string svgPlot(const PlotAxis& x, const PlotAxis& y, const std::vector<PlotSeries>& series,
                    const std::vector<PlotMarker>& markers, const PlotFrame& frame) {
    std::ostringstream s;
    s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << frame.width << "' height='"
      << frame.height
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' "
         "fill='white'/>\n";
    SvgCanvas canvas(s);
    drawPlot(canvas, x, y, series, markers, frame);
    s << "</svg>\n";
    return s.str();
}

ImageRGB plotImage(const PlotAxis& x, const PlotAxis& y, const std::vector<PlotSeries>& series,
                   const std::vector<PlotMarker>& markers, const PlotFrame& frame) {
    RasterCanvas canvas(std::max(1, int(std::lround(frame.width))),
                        std::max(1, int(std::lround(frame.height))));
    drawPlot(canvas, x, y, series, markers, frame);
    return std::move(canvas.image());
}

}  // namespace lh
