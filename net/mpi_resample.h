// Differentiable resampling of an MPI onto the nested cubes of the lighting volume
// (docs/method.md#resampling-into-the-nested-cubes). Every voxel centre is projected into the
// reference camera, its fractional plane index found from its disparity, and the MPI sampled
// trilinearly in (row, column, plane) with premultiplied colour; voxels outside the frustum or the
// depth range are empty.
//
// Cubes are [1, 4, R, R, R] tensors indexed [channel, z, y, x] holding linear RGB and the
// voxel opacity alpha_v = 1 - exp(-sigma * voxelSize) (docs/conventions.md#lighting-volume), so the
// density is sigma = -ln(1 - alpha_v) / voxelSize. MPI plane alpha covers one plane spacing, which
// at depth z is z^2 times the disparity step: alpha_v = 1 - (1 - alpha)^(voxelSize / spacing).
#pragma once

#include "core/camera.h"
#include "net/torch_pch.h"
#include "vdb/volume_layout.h"

#include <vector>

namespace lh::net {

// Largest voxel opacity kept finite (optical depth 9.2 per voxel).
constexpr double kMaxVoxelAlpha = 1.0 - 1e-4;

// World positions of level k's voxel centres, [R, R, R, 3] indexed [z, y, x], float64.
torch::Tensor voxelCentres(const VolumeLayout& layout, int level);

// Colour ceiling of resampled HDR MPIs: un-premultiplying by a tiny alpha must not invent
// radiance brighter than any the MPI holds (net/hdr.h's largest is 8103).
constexpr double kMaxMpiRadiance = 1e4;

// mpi [1, 4, D, H, W] with planes far (0) to near (D-1) at `depths` -> level cube [1, 4, R, R, R].
// Colours are clamped to [0, maxRadiance]: 1 for sigmoid models, kMaxMpiRadiance for HDR ones.
torch::Tensor resampleMpiToLevel(const torch::Tensor& mpi, const std::vector<double>& depths,
                                 const PinholeCamera& ref, const VolumeLayout& layout, int level,
                                 double maxRadiance = 1.0);

// sigma (per scene unit) of a cube's alpha channel.
torch::Tensor densityFromAlpha(const torch::Tensor& alpha, double voxelSize);

}  // namespace lh::net
