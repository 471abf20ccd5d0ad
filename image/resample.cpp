#include "image/resample.h"

#include "core/errors.h"

#include <algorithm>
#include <cmath>

namespace lh {

ImageRGB resizeImage(const ImageRGB& image, int width, int height) {
    if (image.empty() || width < 1 || height < 1)
        throw InputError("resizeImage: empty image or size");
    ImageRGB out(width, height);
    const double sx = double(image.width) / width, sy = double(image.height) / height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            // Average the source pixels under the target pixel's footprint (at least one).
            const double x0 = x * sx, x1 = std::max(x0 + 1e-9, (x + 1) * sx);
            const double y0 = y * sy, y1 = std::max(y0 + 1e-9, (y + 1) * sy);
            double sum[3] = {0, 0, 0}, weight = 0;
            for (int py = int(std::floor(y0)); py < std::min(image.height, int(std::ceil(y1)));
                 ++py)
                for (int px = int(std::floor(x0)); px < std::min(image.width, int(std::ceil(x1)));
                     ++px) {
                    const double w = (std::min<double>(px + 1, x1) - std::max<double>(px, x0)) *
                                     (std::min<double>(py + 1, y1) - std::max<double>(py, y0));
                    if (w <= 0) continue;
                    for (int c = 0; c < 3; ++c) sum[c] += w * image.at(px, py)[c];
                    weight += w;
                }
            if (weight <= 0) {  // growing: nearest source pixel
                const int px = std::min(image.width - 1, int(x0)),
                          py = std::min(image.height - 1, int(y0));
                for (int c = 0; c < 3; ++c) out.at(x, y)[c] = image.at(px, py)[c];
                continue;
            }
            for (int c = 0; c < 3; ++c) out.at(x, y)[c] = float(sum[c] / weight);
        }
    return out;
}

}  // namespace lh
