// Equirectangular envmap layout (CONVENTIONS.md). Pixel (row r, column c) of a W x H map,
// continuous centre (r + 0.5, c + 0.5):
//   phi   = pi * (r + 0.5) / H            (polar angle from up, -y)
//   theta = 2 pi (c + 0.5) / W - pi       (azimuth, 0 = forward +z)
//   d     = (sin phi sin theta, -cos phi, sin phi cos theta)
// Row 0 looks up (-y), column W/2 forward (+z), column 3W/4 right (+x), column W/4 left (-x).
#pragma once

#include "core/camera.h"

#include <cmath>

namespace lh {

// Direction (unit, world frame) through continuous pixel coordinates (row, column); pixel
// centres are at integer + 0.5.
inline Vec3d envmapDirection(double row, double column, int width, int height) {
    const double phi = M_PI * row / height;
    const double theta = 2.0 * M_PI * column / width - M_PI;
    return Vec3d(std::sin(phi) * std::sin(theta), -std::cos(phi), std::sin(phi) * std::cos(theta));
}

inline Vec3d envmapPixelDirection(int row, int column, int width, int height) {
    return envmapDirection(row + 0.5, column + 0.5, width, height);
}

// Inverse: continuous (row, column) where a unit direction lands; column in [0, W).
struct EnvmapCoord {
    double row;
    double column;
};
inline EnvmapCoord envmapCoordinate(const Vec3d& d, int width, int height) {
    const double phi = std::acos(std::clamp(-d.y(), -1.0, 1.0));
    double theta = std::atan2(d.x(), d.z());  // in (-pi, pi]
    double column = (theta + M_PI) / (2.0 * M_PI) * width;
    if (column >= width) column -= width;
    return {phi / M_PI * height, column};
}

}  // namespace lh
