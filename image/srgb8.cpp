#include "image/srgb8.h"

#include "image/image_io.h"

#include <array>

namespace lh {

std::uint8_t srgb8FromLinear(float linear) {
    const float clamped = linear > 0.0f ? (linear < 1.0f ? linear : 1.0f) : 0.0f;  // NaN -> 0
    return std::uint8_t(srgbEncode(clamped) * 255.0f + 0.5f);  // in [0.5, 255.5): rounds
}

float linearFromSrgb8(std::uint8_t code) {
    static const std::array<float, 256> toLinear = [] {
        std::array<float, 256> table{};
        for (int i = 0; i < 256; ++i) table[i] = srgbDecode(float(i) / 255.0f);
        return table;
    }();
    return toLinear[code];
}

}  // namespace lh
