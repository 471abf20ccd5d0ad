// The observed colour at each height of the room, as extra inputs of the completion networks.
//
// Rooms are layered: the floor at the bottom, walls in the middle, the ceiling at the top, and
// an unseen part of the floor, a wall or the ceiling looks like the part the photo shows. A 3D
// U-Net can carry that across the volume in principle, but ours did not learn to: unseen
// ceilings came out as bright as the training rooms' ceilings, whatever colour the photo showed.
// The profile hands it over directly: per horizontal slice of level 0 (world +y is down), the
// mean colour of what the MPI put there, weighted by opacity, and how much of the slice that is.
#pragma once

#include "net/torch_pch.h"
#include "vdb/volume_layout.h"

namespace lh::net {

// Channels the profile adds to each completion network's input: colour feature (3), coverage (1).
constexpr int kHeightProfileChannels = 4;

// Per slice y of a cube [1, 4, R(z), R(y), R(x)] of (linear rgb, alpha): the alpha-weighted
// mean colour over z and x, and the coverage 1 - exp(-(sum of alpha) / R) in [0, 1) (one full
// row of opaque voxels gives 0.63). A slice without matter has colour 0 and coverage 0.
// Returns [1, 4, R].
torch::Tensor heightProfile(const torch::Tensor& cube);

// The profile of level 0 (of `layout`) as input channels of level `level`'s network, at
// `networkResolution` voxels per side: each voxel gets the profile of the level-0 slice that
// holds its centre's height (nearest; heights outside level 0 take its end slices). The colour
// is ln(1 + rgb) when `hdr`, as the cubes' own features. Returns [1, 4, r, r, r].
torch::Tensor heightProfileFeatures(const torch::Tensor& profile, const VolumeLayout& layout,
                                    int level, int networkResolution, bool hdr);

}  // namespace lh::net
