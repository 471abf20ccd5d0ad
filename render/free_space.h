// Query points for measuring envmaps: where a user would ask for the light, in the air of the
// scene, not inside a wall.
#pragma once

#include "render/render_volume.h"

#include <cstdint>
#include <vector>

namespace lh {

// Points uniformly inside level 1's box (level 0's for one-level volumes) where the medium is
// empty. A volume without empty space there (predicted volumes are dense low-alpha fog) gets
// the least dense of 64 x count random points in that box instead. Deterministic for a seed.
// Throws InputError for a volume without levels or without enough sampled points.
std::vector<Vec3d> freeSpacePoints(const RenderVolume& volume, int count, uint64_t seed);

}  // namespace lh
