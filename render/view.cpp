#include "render/view.h"

#include "core/errors.h"
#include "render/envmap.h"

#include <tbb/parallel_for.h>

namespace lh {

ImageRGB renderView(const RenderVolume& volume, const PinholeCamera& camera,
                    const MarchOptions& options) {
    camera.validate("view camera");
    options.validate();
    if (static_cast<long long>(camera.width) * camera.height > kMaxEnvmapPixels)
        throw ResourceError("view of " + std::to_string(camera.width) + "x" +
                            std::to_string(camera.height) + " pixels exceeds the memory bound");
    ImageRGB image(camera.width, camera.height);
    tbb::parallel_for(
        tbb::blocked_range<int>(0, camera.height), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y != rows.end(); ++y)
                for (int x = 0; x < camera.width; ++x) {
                    const Vec3d d = camera.pixelDirection(x + 0.5, y + 0.5);
                    const RayResult ray = marchRay(volume, camera.position, d, options);
                    float* px = image.at(x, y);
                    for (int i = 0; i < 3; ++i) px[i] = float(ray.radiance[i]);
                }
        });
    return image;
}

}  // namespace lh
