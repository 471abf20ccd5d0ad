// Perspective rendering of a lighting volume from a pinhole camera (to look at volumes).
#pragma once

#include "core/camera.h"
#include "image/image.h"
#include "render/ray_marcher.h"

namespace lh {

// One ray through each pixel centre, starting at the camera centre. Rows run in parallel.
ImageRGB renderView(const RenderVolume& volume, const PinholeCamera& camera,
                    const MarchOptions& options = {});

}  // namespace lh
