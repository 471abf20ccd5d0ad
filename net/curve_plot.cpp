#include "net/curve_plot.h"

#include "core/atomic_file.h"
#include "image/image.h"
#include "image/image_io.h"

#include <stb/stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace lh::net {

namespace {

constexpr int kPanelWidth = 720, kPanelHeight = 170, kMarginLeft = 70, kMarginTop = 28, kMarginBottom = 34;
constexpr int kTextScale = 2;

void fillRect(ImageRGB& im, int x0, int y0, int x1, int y1, const float c[3]) {
    for (int y = std::max(0, y0); y < std::min(im.height, y1); ++y)
        for (int x = std::max(0, x0); x < std::min(im.width, x1); ++x) std::copy(c, c + 3, im.at(x, y));
}

// stb_easy_font emits axis-aligned quads; each is a filled rectangle, scaled up.
void drawText(ImageRGB& im, int x, int y, const std::string& text, const float c[3]) {
    static char buffer[99999];
    const int quads = stb_easy_font_print(0, 0, const_cast<char*>(text.c_str()), nullptr, buffer, sizeof(buffer));
    for (int q = 0; q < quads; ++q) {
        const float* v = reinterpret_cast<const float*>(buffer + q * 4 * 16);
        const float* v2 = reinterpret_cast<const float*>(buffer + q * 4 * 16 + 2 * 16);
        fillRect(im, x + int(v[0] * kTextScale), y + int(v[1] * kTextScale), x + int(v2[0] * kTextScale),
                 y + int(v2[1] * kTextScale), c);
    }
}

void drawLine(ImageRGB& im, double x0, double y0, double x1, double y1, const float c[3]) {
    const int steps = int(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
    for (int s = 0; s <= steps; ++s) {
        const double t = double(s) / steps;
        const int x = int(std::lround(x0 + (x1 - x0) * t)), y = int(std::lround(y0 + (y1 - y0) * t));
        fillRect(im, x, y, x + 2, y + 2, c);
    }
}

std::string formatNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof(text), std::abs(v) >= 1000 || (v != 0 && std::abs(v) < 0.01) ? "%.2e" : "%.3g", v);
    return text;
}

}  // namespace

void writeCurvePlot(const std::string& path, const std::string& title, const std::string& xLabel,
                    const std::vector<CurveSeries>& series) {
    const int panels = std::max<int>(1, int(series.size()));
    const int width = kMarginLeft + kPanelWidth + 20;
    const int height = kMarginTop + panels * (kPanelHeight + kMarginBottom);
    ImageRGB im(width, height);
    const float white[3] = {1, 1, 1}, black[3] = {0, 0, 0}, light[3] = {0.85f, 0.85f, 0.85f},
                blue[3] = {0.05f, 0.2f, 0.7f};
    std::fill(im.pixels.begin(), im.pixels.end(), 1.f);
    fillRect(im, 0, 0, width, height, white);
    drawText(im, kMarginLeft, 6, title, black);

    double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin;
    for (const auto& s : series)
        for (double x : s.x) xmin = std::min(xmin, x), xmax = std::max(xmax, x);
    if (!(xmax > xmin)) xmin = 0, xmax = 1;

    for (int p = 0; p < int(series.size()); ++p) {
        const auto& s = series[size_t(p)];
        const int top = kMarginTop + p * (kPanelHeight + kMarginBottom);
        double ymin = std::numeric_limits<double>::infinity(), ymax = -ymin;
        for (double y : s.y)
            if (std::isfinite(y)) ymin = std::min(ymin, y), ymax = std::max(ymax, y);
        if (!(ymax > ymin)) ymin = std::isfinite(ymin) ? ymin - 1 : 0, ymax = ymin + 2;
        const auto toX = [&](double x) { return kMarginLeft + (x - xmin) / (xmax - xmin) * (kPanelWidth - 1); };
        const auto toY = [&](double y) { return top + (ymax - y) / (ymax - ymin) * (kPanelHeight - 1); };
        for (int g = 0; g <= 4; ++g) {  // grid lines and y labels
            const double y = ymin + (ymax - ymin) * g / 4;
            fillRect(im, kMarginLeft, int(toY(y)), kMarginLeft + kPanelWidth, int(toY(y)) + 1, light);
            drawText(im, 2, int(toY(y)) - 6, formatNumber(y), black);
        }
        fillRect(im, kMarginLeft, top, kMarginLeft + 1, top + kPanelHeight, black);
        fillRect(im, kMarginLeft, top + kPanelHeight, kMarginLeft + kPanelWidth, top + kPanelHeight + 1, black);
        for (size_t i = 1; i < s.x.size() && i < s.y.size(); ++i)
            if (std::isfinite(s.y[i - 1]) && std::isfinite(s.y[i]))
                drawLine(im, toX(s.x[i - 1]), toY(s.y[i - 1]), toX(s.x[i]), toY(s.y[i]), blue);
        drawText(im, kMarginLeft + 8, top + 4, s.name, blue);
        drawText(im, kMarginLeft, top + kPanelHeight + 6, formatNumber(xmin), black);
        drawText(im, kMarginLeft + kPanelWidth - 70, top + kPanelHeight + 6, formatNumber(xmax), black);
        drawText(im, kMarginLeft + kPanelWidth / 2 - 30, top + kPanelHeight + 6, xLabel, black);
    }
    writePng(im, path);  // image_io writes through a temporary name
}

}  // namespace lh::net
