// Editing lighting volumes by hand (for users without a DCC): add emissive boxes and spheres,
// erase or crop to a box, scale exposure or density, clamp values. Every level is edited, so
// the result does not depend on which level ends up finest at a point.
#pragma once

#include "vdb/lighting_volume.h"

#include <cstddef>

namespace lh {

// Voxels whose centre lies in the box (or sphere) become `sigma` and `radiance`. Each returns
// how many voxels it changed (over all levels): 0 when the shape misses every voxel centre.
std::size_t addEmissiveBox(LightingVolume& volume, const WorldBox& box,
                           const openvdb::Vec3s& radiance, float sigma);
std::size_t addEmissiveSphere(LightingVolume& volume, const Vec3d& centre, double radius,
                              const openvdb::Vec3s& radiance, float sigma);
// Voxels whose centre lies in the box become empty; returns how many.
std::size_t eraseBox(LightingVolume& volume, const WorldBox& box);
// Everything outside the box becomes empty; each level's domain shrinks to the box.
void cropToBox(LightingVolume& volume, const WorldBox& box);
void scaleExposure(LightingVolume& volume, float factor);  // colour *= factor
void scaleDensity(LightingVolume& volume, float factor);   // sigma *= factor
void clampValues(LightingVolume& volume, float maxDensity, float maxRadiance);

}  // namespace lh
