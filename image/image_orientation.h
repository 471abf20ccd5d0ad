// EXIF orientation: cameras store a photo as the sensor saw it and record in the EXIF
// Orientation tag (1..8) how to turn it upright. Phones in portrait store landscape pixels
// with orientation 6. Every photo is used upright: readImage applies the tag.
#pragma once

#include "image/image.h"

#include <string>

namespace lh {

// The EXIF Orientation of a JPEG (read with libexif), 1 (as stored) when the file has no
// EXIF block, no such tag, or a value outside 1..8.
int exifOrientation(const std::string& path);

// The stored pixel (sx, sy) shown at upright (x, y), for a stored image of w x h pixels.
inline void storedPixelOf(int orientation, int x, int y, int w, int h, int& sx, int& sy) {
    switch (orientation) {
        case 2:
            sx = w - 1 - x;
            sy = y;
            break;
        case 3:
            sx = w - 1 - x;
            sy = h - 1 - y;
            break;
        case 4:
            sx = x;
            sy = h - 1 - y;
            break;
        case 5:
            sx = y;
            sy = x;
            break;
        case 6:
            sx = y;
            sy = h - 1 - x;
            break;
        case 7:
            sx = w - 1 - y;
            sy = h - 1 - x;
            break;
        case 8:
            sx = w - 1 - y;
            sy = x;
            break;
        default:
            sx = x;
            sy = y;
            break;
    }
}

// The upright image for EXIF `orientation` of a stored image of width x height, built in one
// pass from `storedRgb(sx, sy, float* rgb)`, which writes stored pixel (sx, sy): no copy of the
// stored image is made, so readImage holds the decoder's bytes and one float image, not two.
template <typename StoredRgb>
ImageRGB uprightImage(int width, int height, int orientation, StoredRgb storedRgb) {
    if (orientation < 1 || orientation > 8) orientation = 1;
    const bool swapAxes = orientation >= 5;
    ImageRGB upright(swapAxes ? height : width, swapAxes ? width : height);
    for (int y = 0; y < upright.height; ++y)
        for (int x = 0; x < upright.width; ++x) {
            int sx = 0, sy = 0;
            storedPixelOf(orientation, x, y, width, height, sx, sy);
            storedRgb(sx, sy, upright.at(x, y));
        }
    return upright;
}

// The upright image for EXIF `orientation` (1..8; anything else returns `stored`):
// 2 mirror left-right, 3 rotate 180, 4 mirror top-bottom, 5 transpose, 6 rotate 90
// clockwise, 7 transverse, 8 rotate 90 counter-clockwise. 5..8 swap width and height.
ImageRGB applyOrientation(const ImageRGB& stored, int orientation);

}  // namespace lh
