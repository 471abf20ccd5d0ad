// Equirectangular envmap layout (docs/conventions.md#envmap-layout). Pixel (row r, column c) of a W
// x H map, continuous centre (r + 0.5, c + 0.5):
//   phi   = pi * (r + 0.5) / H            (polar angle from up, -y)
//   theta = 2 pi (c + 0.5) / W - pi       (azimuth, 0 = forward +z)
//   d     = (sin phi sin theta, -cos phi, sin phi cos theta)
// Row 0 looks up (-y), column W/2 forward (+z), column 3W/4 right (+x), column W/4 left (-x).
#pragma once

#include "core/vec.h"

#include <cmath>

namespace lh {

// Polar angle phi of a continuous row, azimuth theta of a continuous column (radians).
inline double envmapPolarAngle(double row, int height) { return M_PI * row / height; }
inline double envmapAzimuth(double column, int width) { return 2.0 * M_PI * column / width - M_PI; }

// The direction from the sines and cosines of phi and theta: renderers that tabulate them per
// row and per column (one sincos each, not one per pixel) share this one formula.
inline Vec3d envmapDirectionFromAngles(double sinPhi, double cosPhi, double sinTheta,
                                       double cosTheta) {
    return Vec3d(sinPhi * sinTheta, -cosPhi, sinPhi * cosTheta);
}

// Direction (unit, world frame) through continuous pixel coordinates (row, column); pixel
// centres are at integer + 0.5.
inline Vec3d envmapDirection(double row, double column, int width, int height) {
    const double phi = envmapPolarAngle(row, height), theta = envmapAzimuth(column, width);
    return envmapDirectionFromAngles(std::sin(phi), std::cos(phi), std::sin(theta),
                                     std::cos(theta));
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
