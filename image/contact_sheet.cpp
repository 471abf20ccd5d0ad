#include "image/contact_sheet.h"

#include "core/errors.h"

#include <algorithm>
#include <cmath>

namespace lh {

ImageRGB resizeImage(const ImageRGB& image, int width, int height) {
    if (image.empty() || width < 1 || height < 1) throw InputError("resizeImage: empty image or size");
    ImageRGB out(width, height);
    const double sx = double(image.width) / width, sy = double(image.height) / height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            // Average the source pixels under the target pixel's footprint (at least one).
            const double x0 = x * sx, x1 = std::max(x0 + 1e-9, (x + 1) * sx);
            const double y0 = y * sy, y1 = std::max(y0 + 1e-9, (y + 1) * sy);
            double sum[3] = {0, 0, 0}, weight = 0;
            for (int py = int(std::floor(y0)); py < std::min(image.height, int(std::ceil(y1))); ++py)
                for (int px = int(std::floor(x0)); px < std::min(image.width, int(std::ceil(x1))); ++px) {
                    const double w = (std::min<double>(px + 1, x1) - std::max<double>(px, x0)) *
                                     (std::min<double>(py + 1, y1) - std::max<double>(py, y0));
                    if (w <= 0) continue;
                    for (int c = 0; c < 3; ++c) sum[c] += w * image.at(px, py)[c];
                    weight += w;
                }
            if (weight <= 0) {  // growing: nearest source pixel
                const int px = std::min(image.width - 1, int(x0)), py = std::min(image.height - 1, int(y0));
                for (int c = 0; c < 3; ++c) out.at(x, y)[c] = image.at(px, py)[c];
                continue;
            }
            for (int c = 0; c < 3; ++c) out.at(x, y)[c] = float(sum[c] / weight);
        }
    return out;
}

ImageRGB contactSheet(const std::vector<std::vector<ImageRGB>>& rows, int tileHeight, int gap) {
    if (rows.empty() || tileHeight < 1) throw InputError("contact sheet: nothing to show");
    std::vector<std::vector<ImageRGB>> scaled;
    int width = 0;
    for (const auto& row : rows) {
        std::vector<ImageRGB> line;
        int w = gap;
        for (const auto& img : row) {
            const int tw = std::max(1, int(std::lround(double(img.width) * tileHeight / img.height)));
            line.push_back(resizeImage(img, tw, tileHeight));
            w += tw + gap;
        }
        width = std::max(width, w);
        scaled.push_back(std::move(line));
    }
    const int height = gap + int(rows.size()) * (tileHeight + gap);
    ImageRGB sheet(width, height);
    std::fill(sheet.pixels.begin(), sheet.pixels.end(), 0.02f);  // dark grey border
    int y = gap;
    for (const auto& line : scaled) {
        int x = gap;
        for (const auto& img : line) {
            for (int py = 0; py < img.height; ++py)
                for (int px = 0; px < img.width; ++px)
                    std::copy(img.at(px, py), img.at(px, py) + 3, sheet.at(x + px, y + py));
            x += img.width + gap;
        }
        y += tileHeight + gap;
    }
    return sheet;
}

}  // namespace lh
