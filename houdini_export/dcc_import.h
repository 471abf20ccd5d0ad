// Reading an export (dcc_export.h), possibly edited in Blender, Houdini or python3-openvdb,
// back into a lighting volume: shells become levels again.
//
// Per level file: `density` (FloatGrid) is required. The radiance comes from `emission`
// (colour = emission / density) when that grid exists, because the DCC material renders
// `emission` and `density`: what the user saw there is what comes back. Without `emission`,
// `color` (Blender) or `Cd` (Houdini) is used. Transforms are rotated back to lighthouse's
// world frame. Each level's domain is the `lighthouse_domain_min/max` grid metadata (or, if
// an edit dropped it, the active bounding box); the coarsest level's domain also grows to
// every active voxel, so content added outside the volume is kept. Voxels a shell holds under
// a finer level, or a finer level holds outside its domain, are ignored with a warning (finest
// wins would hide them). Covered voxels are then refilled from the finer levels
// (shells.h, fillCoveredFromFiner).
#pragma once

#include "houdini_export/dcc_convention.h"
#include "vdb/lighting_volume.h"

#include <string>
#include <vector>

namespace lh {

// Throws FileError naming the file (and grid) if `dir` is not an export for `dcc`, a level file
// is missing or unreadable, or grids have the wrong type or transform. NaN/Inf/negative values
// are replaced (as loadVolume does) and reported in `warnings`.
LightingVolume importFromDcc(const std::string& dir, Dcc dcc, std::vector<std::string>* warnings = nullptr);

}  // namespace lh
