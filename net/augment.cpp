#include "net/augment.h"

#include "render/image_io.h"

#include <algorithm>
#include <cmath>

namespace lh::net {

Augmentation drawAugmentation(Random& rng) {
    Augmentation a;
    a.exposure = std::exp(rng.uniform(-0.6, 0.6));
    for (double& g : a.gain) g = std::exp(rng.uniform(-0.12, 0.12));
    a.noiseSigma = rng.uniform(0.0, 2.5) / 255.0;
    return a;
}

namespace {

// Standard normal by Box-Muller.
double gaussian(Random& rng) {
    const double u = std::max(rng.uniform(), 1e-12), v = rng.uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * M_PI * v);
}

}  // namespace

void augmentPhoto(ImageRGB& photo, const Augmentation& a, Random& rng) {
    for (std::size_t i = 0; i < photo.pixels.size(); ++i) {
        const float linear = std::clamp(float(photo.pixels[i] * a.factor(int(i % 3))), 0.f, 1.f);
        double code = srgbEncode(linear);
        if (a.noiseSigma > 0) code += a.noiseSigma * gaussian(rng);
        code = std::round(std::clamp(code, 0.0, 1.0) * 255.0) / 255.0;
        photo.pixels[i] = srgbDecode(float(code));
    }
}

void augmentRadiance(ImageRGB& radiance, const Augmentation& a) {
    for (std::size_t i = 0; i < radiance.pixels.size(); ++i)
        radiance.pixels[i] = float(radiance.pixels[i] * a.factor(int(i % 3)));
}

}  // namespace lh::net
