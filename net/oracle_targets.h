// Targets of direct (voxel) supervision: an example's oracle volume (oracle.vdb, written by
// `lighthouse synth --oracle-levels L`) as the network's cubes.
//
// The oracle is stored sparse in the layout of the example's far depth (synth/oracle.h). Its
// levels become dense cubes [1, 4, R, R, R] (linear RGB, voxel alpha 1 - exp(-sigma voxel)),
// the form the completion networks output, so a voxel loss compares them directly. Where the
// network's resolution is lower than the oracle's (R = R_oracle / f), f^3 blocks are
// averaged: alpha plainly, colour weighted by alpha.
#pragma once

#include "net/torch_pch.h"
#include "vdb/volume_layout.h"

#include <string>
#include <vector>

namespace lh::net {

// Throws FileError when the file is unreadable or its layout is not `layout` at an integer
// multiple of its resolution (another far depth, or another level count).
std::vector<torch::Tensor> loadOracleCubes(const std::string& path, const VolumeLayout& layout,
                                           const torch::Device& device);

}  // namespace lh::net
