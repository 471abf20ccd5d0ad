// The oracle lighting volume of a synthetic scene: its true geometry and radiance voxelised
// into the lighting-volume layout, the best any predictor could output at that resolution.
//
// Per voxel, s^3 sub-samples: the fraction inside solids gives the density
// (sigma = fraction * opacity / voxel size, so a full voxel has optical depth `opacity`), and
// the mean radiance of the nearest surface point of each inside sample gives the colour.
// Voxels farther than a voxel from every surface stay empty: deep inside walls nothing is
// seen, and empty space costs nothing.
#pragma once

#include "synth/radiance_field.h"
#include "vdb/lighting_volume.h"

namespace lh::synth {

struct OracleOptions {
    int supersample = 3;   // sub-samples per voxel and axis
    double opacity = 8.0;  // optical depth of a fully occupied voxel
};

LightingVolume oracleVolume(const Scene& scene, const RadianceField& field,
                            const VolumeLayout& layout, const OracleOptions& options = {});

}  // namespace lh::synth
