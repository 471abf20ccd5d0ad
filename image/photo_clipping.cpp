#include "image/photo_clipping.h"

#include "image/luminance.h"

#include <algorithm>
#include <cstddef>
#include <limits>

namespace lh {

double exposureClippingAtMost(const ImageRGB& linear, const double gain[3], double maxFraction) {
    const std::size_t count = linear.pixels.size() / 3;
    if (count == 0) return std::numeric_limits<double>::infinity();
    std::vector<double> brightest(count);  // each pixel's largest channel after white balance
    for (std::size_t p = 0; p < count; ++p) {
        const float* rgb = &linear.pixels[3 * p];
        brightest[p] = std::max({rgb[0] * gain[0], rgb[1] * gain[1], rgb[2] * gain[2]});
    }
    // At exposure 1/v exactly the pixels brighter than v clip: v is the value with at most
    // floor(maxFraction * count) pixels above it.
    const std::size_t allowed =
        std::min(count - 1, std::size_t(std::clamp(maxFraction, 0.0, 1.0) * double(count)));
    const auto v = brightest.begin() + long(count - 1 - allowed);
    std::nth_element(brightest.begin(), v, brightest.end());
    return *v > 0 ? 1.0 / *v : std::numeric_limits<double>::infinity();
}

std::vector<double> clippedLuminances(const ImageRGB& linear, double exposure) {
    std::vector<double> out;
    for (std::size_t i = 0; i + 2 < linear.pixels.size(); i += 3) {
        const float* rgb = &linear.pixels[i];
        if (exposure * std::max({rgb[0], rgb[1], rgb[2]}) > 1.0)
            out.push_back(exposure * rec709Luminance(rgb));
    }
    return out;
}

}  // namespace lh
