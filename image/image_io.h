// Reading and writing ImageRGB: linear float EXR for data, sRGB 8-bit PNG for viewing.
// Errors are typed (core/errors.h): FileError for anything about a file, InputError for
// an unusable image or format request, ResourceError for absurd image sizes.
#pragma once

#include "image/image.h"

#include <cstdint>
#include <string>

namespace lh {

// Largest image read or written, in pixels (2^28 = 16384^2): bounds memory at 3 GiB of
// float RGB (3.75 GiB while a PNG or JPEG is read: the decoder's 8-bit pixels and the float
// image, 15 bytes a pixel) and rejects corrupt headers that claim gigantic sizes.
constexpr std::int64_t kMaxImagePixels = std::int64_t(1) << 28;

// The exact sRGB transfer functions (IEC 61966-2-1), linear <-> encoded, both in [0,1].
float srgbEncode(float linear);
float srgbDecode(float encoded);

// Linear values as they are, 32-bit float R, G, B channels, ZIP compression.
void writeExr(const ImageRGB& image, const std::string& path);

// Multiplies by `exposure` (> 0), clamps to [0,1] (NaN -> 0), sRGB-encodes, 8 bits.
void writePng(const ImageRGB& image, const std::string& path, float exposure = 1.0f);

// Chooses the writer from the extension (.exr or .png). EXR ignores `exposure`: it keeps
// the linear values so no information is lost.
void writeImage(const ImageRGB& image, const std::string& path, float exposure = 1.0f);

// Reads .exr (R, G, B of any pixel type, or Y replicated to grey) as linear values, and
// .png / .jpg / .jpeg (8-bit sRGB) decoded to linear and turned upright by the JPEG's EXIF
// Orientation (image/image_orientation.h).
ImageRGB readImage(const std::string& path);

}  // namespace lh
