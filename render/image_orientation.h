// EXIF orientation: cameras store a photo as the sensor saw it and record in the EXIF
// Orientation tag (1..8) how to turn it upright. Phones in portrait store landscape pixels
// with orientation 6. Every photo is used upright: readImage applies the tag.
#pragma once

#include "render/image.h"

#include <string>

namespace lh {

// The EXIF Orientation of a JPEG (read with libexif), 1 (as stored) when the file has no
// EXIF block, no such tag, or a value outside 1..8.
int exifOrientation(const std::string& path);

// The upright image for EXIF `orientation` (1..8; anything else returns `stored`):
// 2 mirror left-right, 3 rotate 180, 4 mirror top-bottom, 5 transpose, 6 rotate 90
// clockwise, 7 transverse, 8 rotate 90 counter-clockwise. 5..8 swap width and height.
ImageRGB applyOrientation(const ImageRGB& stored, int orientation);

}  // namespace lh
