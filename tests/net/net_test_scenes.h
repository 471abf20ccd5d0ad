// Scenes with known answers for the network tests: pinhole cameras looking down +z at a
// fronto-parallel textured plane, rendered analytically.
#pragma once

#include "core/camera.h"
#include "image/image.h"
#include "net/config.h"

#include <cmath>

namespace lh::test {

inline PinholeCamera planeCamera(int width, int height, const Vec3d& position = Vec3d(0.0)) {
    PinholeCamera c;
    c.width = width;
    c.height = height;
    c.fx = c.fy = 0.8 * width;
    c.cx = width / 2.0;
    c.cy = height / 2.0;
    c.position = position;
    return c;
}

// Deterministic hash of an integer cell and channel -> [0, 1).
inline double cellNoise(long long i, long long j, int channel) {
    unsigned long long h = (unsigned long long)(i * 73856093LL) ^
                           (unsigned long long)(j * 19349663LL) ^
                           (unsigned long long)(channel * 83492791LL);
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    return double(h % 10007) / 10007.0;
}

// Linear texture on the plane, by world position (x, y): value noise on 15 cm cells,
// bilinearly interpolated, so it is continuous and has no period a stereo matcher could
// confuse.
inline void planeTexture(double x, double y, float rgb[3]) {
    const double u = x / 0.15, v = y / 0.15;
    const long long i = (long long)std::floor(u), j = (long long)std::floor(v);
    const double a = u - double(i), b = v - double(j);
    for (int c = 0; c < 3; ++c)
        rgb[c] = float(
            0.1 + 0.8 * ((cellNoise(i, j, c) * (1 - a) + cellNoise(i + 1, j, c) * a) * (1 - b) +
                         (cellNoise(i, j + 1, c) * (1 - a) + cellNoise(i + 1, j + 1, c) * a) * b));
}

// What `camera` sees of the plane z = depth (world frame); cameras look down +z.
inline ImageRGB renderPlane(const PinholeCamera& camera, double depth) {
    ImageRGB image(camera.width, camera.height);
    for (int v = 0; v < camera.height; ++v)
        for (int u = 0; u < camera.width; ++u) {
            const Vec3d d = camera.pixelDirection(u + 0.5, v + 0.5);
            const double s = (depth - camera.position.z()) / d.z();
            const Vec3d p = camera.position + d * s;
            planeTexture(p.x(), p.y(), image.at(u, v));
        }
    return image;
}

// A configuration small enough for unit tests: 32x16 input, 16 planes, 2 x 16^3.
inline net::NetConfig tinyConfig() {
    net::NetConfig c;
    c.name = "tiny";
    c.width = 32;
    c.height = 16;
    c.planes = 16;
    c.levels = 2;
    c.resolution = 16;
    c.baseWidth = 2;
    c.trainEnvWidth = 16;
    c.trainEnvHeight = 8;
    c.samplesPerLevel = 32;
    return c;
}

// The `standard` configuration's design at unit-test sizes: a 2D MPI network, HDR colours,
// completion networks at half the cube resolution (2 x 32^3 cubes, completed at 16^3), and
// invented colours relative to the photo's mean colour.
inline net::NetConfig tinyHdrConfig() {
    net::NetConfig c = tinyConfig();
    c.name = "tiny-hdr";
    c.resolution = 32;
    c.mpiNetwork = "2d";
    c.mpiWidth = 4;
    c.baseWidth = 4;
    c.completionScale = 2;
    c.hdr = true;
    c.colourAnchor = true;
    return c;
}

}  // namespace lh::test
