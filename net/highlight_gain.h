// Expanding a predicted volume's lamps and windows. The model shows where the photo saw a lamp
// or a window, but only a little brighter than white: a voxel can only show a lamp smaller
// than itself spread over its width, so the losses keep it near 1 (docs/network.md, "Where the
// lamps and windows are"), while the true lamps reach tens to hundreds. Multiplying what a
// voxel holds above white by a gain puts back some of the light a diffuse object would
// receive. Voxels at or below white and every voxel's hue stay as they were, so an envmap
// changes only where a voxel above white shows (predict --highlight-gain, docs/network.md).
//
// The knee moves where the expansion starts: a voxel of luminance Y above it becomes
// knee + gain (Y - knee). Around each lamp the model leaves voxels a little above white;
// expanded, they draw the lamp too wide on a mirror ball (on dev_cycles nearly all the false
// highlights of a gain lie 10-30 degrees from a true lamp). A knee above 1 (predict
// --highlight-knee) expands only the brighter core.
//
// The expansion itself is expandHighlightsInCubes (net/volume_render.h), applied to the cubes
// both in training (knee 1) and before predict turns them into grids.
#pragma once

#include "net/config.h"

namespace lh::net {

// Throws InputError naming --highlight-gain unless gain is in [1, kMaxHighlightGain].
void validateHighlightGain(double gain);
// Throws InputError naming --highlight-knee unless knee is in [1, kMaxHighlightKnee].
void validateHighlightKnee(double knee);

}  // namespace lh::net
