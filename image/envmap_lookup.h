// Looking up an equirectangular envmap (docs/conventions.md#envmap-layout) along a direction,
// bilinear, wrapping around in azimuth and clamping at the poles.
#pragma once

#include "image/envmap_layout.h"
#include "image/image.h"

#include <algorithm>
#include <cmath>

namespace lh {

inline Vec3d sampleEnvmap(const ImageRGB& envmap, const Vec3d& direction) {
    const EnvmapCoord pc = envmapCoordinate(direction, envmap.width, envmap.height);
    const double fx = pc.column - 0.5, fy = std::clamp(pc.row - 0.5, 0.0, envmap.height - 1.0);
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const double wx = fx - x0, wy = fy - y0;
    const int y1 = std::min(y0 + 1, envmap.height - 1);
    const auto wrap = [&](int x) { return (x % envmap.width + envmap.width) % envmap.width; };
    Vec3d result(0.0);
    for (int c = 0; c < 3; ++c) {
        const double top =
            (1 - wx) * envmap.at(wrap(x0), y0)[c] + wx * envmap.at(wrap(x0 + 1), y0)[c];
        const double bottom =
            (1 - wx) * envmap.at(wrap(x0), y1)[c] + wx * envmap.at(wrap(x0 + 1), y1)[c];
        result[c] = (1 - wy) * top + wy * bottom;
    }
    return result;
}

}  // namespace lh
