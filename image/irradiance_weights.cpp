#include "image/irradiance_weights.h"

#include "core/errors.h"
#include "image/envmap_layout.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace lh {

namespace {

// The unit axis normals in AxisNormal order.
const Vec3d kNormals[kAxisNormals] = {Vec3d(1, 0, 0),  Vec3d(-1, 0, 0), Vec3d(0, 1, 0),
                                      Vec3d(0, -1, 0), Vec3d(0, 0, 1),  Vec3d(0, 0, -1)};

}  // namespace

std::vector<double> axisIrradianceWeights(int width, int height) {
    if (width < 1 || height < 1)
        throw InputError("irradiance weights need an envmap of at least 1x1, got " +
                         std::to_string(width) + "x" + std::to_string(height));
    std::vector<double> weights(std::size_t(width) * std::size_t(height) * kAxisNormals);
    const double pixelArea = (2.0 * M_PI / width) * (M_PI / height);  // sr per unit sin(phi)
    double* w = weights.data();
    for (int r = 0; r < height; ++r) {
        const double solidAngle = pixelArea * std::sin(envmapPolarAngle(r + 0.5, height));
        for (int c = 0; c < width; ++c) {
            const Vec3d d = envmapPixelDirection(r, c, width, height);
            for (int n = 0; n < kAxisNormals; ++n)
                *w++ = std::max(0.0, kNormals[n].dot(d)) * solidAngle;
        }
    }
    return weights;
}

}  // namespace lh
