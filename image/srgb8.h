// 8-bit sRGB codes <-> linear values: what a PNG or JPEG stores, and what the renderer and
// the network work in. One pair of conversions for every 8-bit writer and reader (PNG and
// JPEG files, and the JPEG augmentation of training photos), so that all of them round the
// same way.
#pragma once

#include <cstdint>

namespace lh {

// clamp(linear, 0, 1) (NaN -> 0), sRGB-encoded and rounded to the nearest of 256 codes.
std::uint8_t srgb8FromLinear(float linear);

// The linear value of an 8-bit sRGB code, from a table of the 256 exact decodings.
float linearFromSrgb8(std::uint8_t code);

}  // namespace lh
