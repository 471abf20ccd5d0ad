// Differentiable envmap rendering for training, in the density/colour convention of
// docs/conventions.md#lighting-volume, so that it and the C++ ray marcher integrate the same
// medium.
//
// Like the paper, each level is sampled on `samplesPerLevel` concentric spheres around the
// query point, evenly spaced out to the level's farthest corner. Unlike the paper, a sample
// counts only where its level is the finest one containing it (finest wins, no zeroed coarse
// voxels), sigma and premultiplied emission sigma * colour are interpolated trilinearly, and
// each sample integrates exactly over its shell thickness dt:
//   L += T * colour * (1 - exp(-sigma dt)),  T *= exp(-sigma dt),
// with colour = emission / sigma; nothing is added behind the volume.
#pragma once

#include "core/vec.h"
#include "net/torch_pch.h"
#include "vdb/volume_layout.h"

#include <vector>

namespace lh::net {

// Unit directions of every envmap pixel (docs/conventions.md#envmap-layout), [H, W, 3], float64.
torch::Tensor envmapDirections(int width, int height);

// An envmap and what is left of each of its rays behind the volume.
struct TorchEnvmap {
    torch::Tensor radiance;       // [1, 3, height, width], linear RGB
    torch::Tensor transmittance;  // [1, 1, height, width], exp(-optical depth of the whole ray)
};

// cubes: per level (coarsest first) [1, 4, R, R, R] linear RGB + voxel alpha.
// Renders the envmap at `position` (world frame).
TorchEnvmap renderEnvmapAndTransmittanceTorch(const std::vector<torch::Tensor>& cubes,
                                              const VolumeLayout& layout, const Vec3d& position,
                                              int width, int height, int samplesPerLevel);
// Its radiance alone, [1, 3, height, width].
torch::Tensor renderEnvmapTorch(const std::vector<torch::Tensor>& cubes, const VolumeLayout& layout,
                                const Vec3d& position, int width, int height, int samplesPerLevel);

// The cubes as predict exports them at pruning threshold `minAlpha` (net/volume_export.h):
// voxels whose alpha is below it are empty. The gradient passes as if nothing were pruned
// (straight-through), so a loss that needs a pruned voxel's light can still raise its alpha
// above the threshold. minAlpha <= 0 returns the cubes unchanged.
std::vector<torch::Tensor> pruneCubesStraightThrough(const std::vector<torch::Tensor>& cubes,
                                                     double minAlpha);

// The cubes as predict exports them under a highlight gain (net/highlight_gain.h): each voxel
// of luminance Y above the knee scaled, hue kept, to knee + gain (Y - knee); alpha and
// everything at or below the knee unchanged. Differentiable. gain 1 returns the cubes
// unchanged. Validate the gain and the knee first (net/highlight_gain.h).
std::vector<torch::Tensor> expandHighlightsInCubes(const std::vector<torch::Tensor>& cubes,
                                                   double gain, double knee = 1.0);

}  // namespace lh::net
