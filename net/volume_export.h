// Network tensors -> the project's types: completed cubes -> LightingVolume (OpenVDB grids),
// MPI tensor -> Mpi, so predictions are written with vdb/volume_io like any other volume.
#pragma once

#include "net/torch_pch.h"
#include "vdb/lighting_volume.h"
#include "vdb/mpi.h"

#include <vector>

namespace lh::net {

// Voxels whose opacity over one voxel is below this carry no visible light and are not stored.
constexpr float kMinStoredVoxelAlpha = 1e-4f;

// cubes: per level (coarsest first) [1, 4, R, R, R] linear RGB + voxel alpha, indexed [z, y, x].
// Voxels with alpha below `minAlpha` are left empty (density 0, inactive): the volume's
// sparsity, which empty-space skipping and storage depend on.
LightingVolume cubesToVolume(const std::vector<torch::Tensor>& cubes, const VolumeLayout& layout,
                             float minAlpha = kMinStoredVoxelAlpha);

// mpi: [1, 4, D, H, W] linear RGB + alpha, planes far to near at `depths`.
Mpi tensorToMpi(const torch::Tensor& mpi, const PinholeCamera& camera,
                const std::vector<double>& depths);

}  // namespace lh::net
