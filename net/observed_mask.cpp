#include "net/observed_mask.h"

#include "core/errors.h"

#include <cmath>
#include <optional>
#include <string>

namespace lh::net {

std::vector<std::uint8_t> observedMaskFromDepth(const ImageRGB& positions,
                                                const PinholeCamera& reference,
                                                const ImageRGB& refDepth,
                                                const DepthTolerance& tolerance) {
    if (refDepth.width != reference.width || refDepth.height != reference.height)
        throw InputError("reference depth map is " + std::to_string(refDepth.width) + "x" +
                         std::to_string(refDepth.height) + " but the reference camera is " +
                         std::to_string(reference.width) + "x" + std::to_string(reference.height) +
                         "; give the depth at the camera's resolution");
    std::vector<std::uint8_t> mask(std::size_t(positions.width) * positions.height, 0);
    for (std::size_t p = 0; p < mask.size(); ++p) {
        const float* v = &positions.pixels[3 * p];
        const Vec3d world(v[0], v[1], v[2]);
        if (!world.isFinite()) continue;
        const std::optional<Vec3d> pixel = reference.projectIntoImage(world);
        if (!pixel) continue;
        const double depth = refDepth.at(int(pixel->x()), int(pixel->y()))[0];
        const bool surfaceThere = std::isfinite(depth) && depth > 0.0;
        if (surfaceThere && pixel->z() > depth + tolerance.relative * depth + tolerance.absolute)
            continue;  // something nearer hides it
        mask[p] = 1;
    }
    return mask;
}

}  // namespace lh::net
