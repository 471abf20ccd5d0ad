// The pinhole camera most tests need: square pixels, the principal point at the image centre.
#pragma once

#include "core/camera.h"

namespace lh::test {

// width x height pixels of focal length `focal` (pixels, both axes), the principal point at the
// centre, at `position` looking along +z (the identity rotation): a point (X, Y, Z) in front
// lands on x = width / 2 + focal X / Z, y = height / 2 + focal Y / Z.
inline PinholeCamera centredCamera(int width, int height, double focal,
                                   const Vec3d& position = Vec3d(0.0)) {
    PinholeCamera c;
    c.width = width;
    c.height = height;
    c.fx = c.fy = focal;
    c.cx = width / 2.0;
    c.cy = height / 2.0;
    c.position = position;
    return c;
}

}  // namespace lh::test
