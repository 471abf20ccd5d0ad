#include "net/augment.h"

#include "core/errors.h"
#include "image/image_io.h"
#include "image/srgb8.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace lh::net {

Augmentation drawAugmentation(Random& rng) {
    Augmentation a;
    a.exposure = std::exp(rng.uniform(-0.6, 0.6));
    for (double& g : a.gain) g = std::exp(rng.uniform(-0.12, 0.12));
    a.noiseSigma = rng.uniform(0.0, 2.5) / 255.0;
    if (rng.chance(0.5)) a.jpegQuality = rng.integer(60, 95);
    return a;
}

ImageRGB jpegRoundTrip(const ImageRGB& linear, int quality) {
    std::vector<std::uint8_t> codes(linear.pixels.size());
    for (std::size_t i = 0; i < codes.size(); ++i) codes[i] = srgb8FromLinear(linear.pixels[i]);
    std::vector<std::uint8_t> file;
    const auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<std::uint8_t>*>(context);
        out->insert(out->end(), static_cast<std::uint8_t*>(data),
                    static_cast<std::uint8_t*>(data) + size);
    };
    if (!stbi_write_jpg_to_func(append, &file, linear.width, linear.height, 3, codes.data(),
                                quality))
        throw Error("JPEG augmentation: could not encode a " + std::to_string(linear.width) + "x" +
                    std::to_string(linear.height) + " image");
    int w = 0, h = 0, channels = 0;
    const std::unique_ptr<std::uint8_t, void (*)(void*)> decoded(
        stbi_load_from_memory(file.data(), int(file.size()), &w, &h, &channels, 3),
        stbi_image_free);
    if (!decoded || w != linear.width || h != linear.height)
        throw Error("JPEG augmentation: could not decode the image it encoded");
    ImageRGB out(w, h);
    for (std::size_t i = 0; i < out.pixels.size(); ++i)
        out.pixels[i] = linearFromSrgb8(decoded.get()[i]);
    return out;
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
        photo.pixels[i] =
            linearFromSrgb8(std::uint8_t(std::lround(std::clamp(code, 0.0, 1.0) * 255.0)));
    }
    if (a.jpegQuality > 0) photo = jpegRoundTrip(photo, a.jpegQuality);
}

void augmentRadiance(ImageRGB& radiance, const Augmentation& a) {
    for (std::size_t i = 0; i < radiance.pixels.size(); ++i)
        radiance.pixels[i] = float(radiance.pixels[i] * a.factor(int(i % 3)));
}

}  // namespace lh::net
