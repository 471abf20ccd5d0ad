#include "render/envmap.h"

#include "core/errors.h"
#include "image/envmap_layout.h"
#include "render/first_medium.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace lh {

void EnvmapOptions::validate() const {
    if (width < 2 || height < 1 || width != 2 * height)
        throw InputError("envmap size must be W x H with W = 2 H >= 2, got " +
                         std::to_string(width) + "x" + std::to_string(height));
    if (static_cast<long long>(width) * height > kMaxEnvmapPixels)
        throw ResourceError("envmap " + std::to_string(width) + "x" + std::to_string(height) +
                            " exceeds the " + std::to_string(kMaxEnvmapPixels) +
                            "-pixel memory bound");
    for (float b : background)
        if (!(std::isfinite(b) && b >= 0.f))
            throw InputError("envmap background radiance must be finite and non-negative");
    march.validate();
}

ImageRGB renderEnvmap(const RenderVolume& volume, const Vec3d& position,
                      const EnvmapOptions& options) {
    options.validate();
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(position[a])) throw InputError("envmap position must be finite");
    ImageRGB image(options.width, options.height);
    // envmapPixelDirection factored: one sincos per column and per row, not per pixel.
    std::vector<double> sinTheta(options.width), cosTheta(options.width);
    for (int c = 0; c < options.width; ++c) {
        const double theta = envmapAzimuth(c + 0.5, options.width);
        sinTheta[c] = std::sin(theta), cosTheta[c] = std::cos(theta);
    }
    const RenderVolume::RayOrigin origin = volume.rayOrigin(position);
    // What a pixel whose ray meets no medium shows (a ray with T = 1 and no radiance).
    const float background[3] = {float(options.background[0]), float(options.background[1]),
                                 float(options.background[2])};
    std::optional<FirstMediumMap> firstMedium;
    if (options.startAtFirstMedium && options.march.cellNodes > 0)
        firstMedium.emplace(volume, position, options.width, options.height);
    tbb::parallel_for(
        tbb::blocked_range<int>(0, options.height), [&](const tbb::blocked_range<int>& rows) {
            // Where each ray of these rows first meets the medium (0: from the origin).
            std::vector<float> starts(std::size_t(rows.size()) * options.width, 0.f);
            if (firstMedium) firstMedium->fillRows(rows.begin(), rows.end(), starts.data());
            for (int r = rows.begin(); r != rows.end(); ++r) {
                const double phi = envmapPolarAngle(r + 0.5, options.height);
                const double sinPhi = std::sin(phi), cosPhi = std::cos(phi);
                const float* rowStarts =
                    starts.data() + std::size_t(r - rows.begin()) * options.width;
                for (int c = 0; c < options.width; ++c) {
                    float* px = image.at(c, r);
                    // A ray that never meets the medium sees the background (most
                    // of an envmap's rays in a sparse room: keep them cheap).
                    if (std::isinf(rowStarts[c])) {
                        std::copy(background, background + 3, px);
                        continue;
                    }
                    const Vec3d d =
                        envmapDirectionFromAngles(sinPhi, cosPhi, sinTheta[c], cosTheta[c]);
                    const RayResult ray = marchRay(volume, origin, d, options.march, rowStarts[c]);
                    for (int i = 0; i < 3; ++i)
                        px[i] = float(ray.radiance[i] + ray.transmittance * options.background[i]);
                }
            }
        });
    return image;
}

}  // namespace lh
