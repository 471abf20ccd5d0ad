// Nested levels <-> non-overlapping shells.
//
// Our renderer lets the finest level that contains a point define the medium there. DCC
// renderers instead add every volume that overlaps a point (Cycles sums the absorption and
// emission of all volume objects on a ray). So each level is exported as a shell: the level
// minus every voxel whose centre lies inside a finer level's domain. With the nested layout
// (levels lie on voxel boundaries of their parents) the shells tile space exactly and their sum
// is the finest-wins medium.
#pragma once

#include "vdb/lighting_volume.h"

#include <vector>

namespace lh {

// Deep copies of every level with the voxels a finer level covers removed (inactive, zero).
// Domains are kept: a shell still says which region its level spans.
std::vector<VolumeLevel> makeShells(const LightingVolume& volume);

// Inverse of makeShells on import: every voxel of a level whose centre lies inside a finer
// level gets the premultiplied average of the finer level over the voxel (the mean of sigma
// and of sigma * colour at 2 x 2 x 2 sub-points, colour = mean emission / mean sigma). Finest
// wins never looks at these voxels except through the one-voxel halo that blends a finer
// level into its parent, which then sees the finer level's own content.
void fillCoveredFromFiner(LightingVolume& volume);

}  // namespace lh
