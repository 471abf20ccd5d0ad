#include "image/contact_sheet.h"

#include "core/errors.h"
#include "image/resample.h"

#include <algorithm>
#include <cmath>

namespace lh {

ImageRGB contactSheet(const std::vector<std::vector<ImageRGB>>& rows, int tileHeight, int gap) {
    if (rows.empty() || tileHeight < 1) throw InputError("contact sheet: nothing to show");
    std::vector<std::vector<ImageRGB>> scaled;
    int width = 0;
    for (const auto& row : rows) {
        std::vector<ImageRGB> line;
        int w = gap;
        for (const auto& img : row) {
            const int tw =
                std::max(1, int(std::lround(double(img.width) * tileHeight / img.height)));
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
