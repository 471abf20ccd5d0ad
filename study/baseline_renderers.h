// Two envmap renderers to measure ours against, same layout and medium:
//   * the paper's: per level N concentric spheres around the query point (radii evenly spaced
//     between the level's nearest and farthest points), one trilinear lookup per sphere and
//     pixel, composited front to back; a level contributes only where no finer level exists;
//   * a straightforward fixed-step marcher over OpenVDB's own BoxSampler, what a user would
//     write first: plain trilinear density and colour, a step of `stepVoxels` voxels of the
//     finest level containing the sample, no empty-space skipping, stop at T < 1e-4.
#pragma once

#include "render/envmap.h"

namespace lh {

ImageRGB renderEnvmapConcentricSpheres(const RenderVolume& volume, const Vec3d& position, int width,
                                       int height, int spheresPerLevel = 128);

ImageRGB renderEnvmapOpenVdbFixedStep(const LightingVolume& volume, const Vec3d& position,
                                      int width, int height, double stepVoxels = 0.5);

}  // namespace lh
