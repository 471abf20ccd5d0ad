#include "render/envmap.h"

#include "core/errors.h"
#include "render/envmap_layout.h"

#include <tbb/parallel_for.h>

#include <cmath>

namespace lh {

void EnvmapOptions::validate() const {
    if (width < 2 || height < 1 || width != 2 * height)
        throw InputError("envmap size must be W x H with W = 2 H >= 2, got " +
                         std::to_string(width) + "x" + std::to_string(height));
    if (static_cast<long long>(width) * height > kMaxEnvmapPixels)
        throw ResourceError("envmap " + std::to_string(width) + "x" + std::to_string(height) +
                            " exceeds the " + std::to_string(kMaxEnvmapPixels) +
                            "-pixel memory bound");
    march.validate();
}

ImageRGB renderEnvmap(const RenderVolume& volume, const Vec3d& position,
                      const EnvmapOptions& options) {
    options.validate();
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(position[a]))
            throw InputError("envmap position must be finite");
    ImageRGB image(options.width, options.height);
    tbb::parallel_for(tbb::blocked_range<int>(0, options.height),
                      [&](const tbb::blocked_range<int>& rows) {
                          for (int r = rows.begin(); r != rows.end(); ++r)
                              for (int c = 0; c < options.width; ++c) {
                                  const Vec3d d = envmapPixelDirection(r, c, options.width, options.height);
                                  const RayResult ray = marchRay(volume, position, d, options.march);
                                  float* px = image.at(c, r);
                                  for (int i = 0; i < 3; ++i) px[i] = float(ray.radiance[i]);
                              }
                      });
    return image;
}

}  // namespace lh
