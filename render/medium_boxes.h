// Boxes that bound where a volume's medium can be seen, computed once per RenderVolume.
//
// The renderer's field is zero outside its stored bricks' boxes of occupied cells
// (RenderLevel::cellBox), and under finest-wins a finer level claims its whole domain, so a
// coarse level's medium inside it is never seen. These boxes, in scene units, are what lets
// an envmap find where each ray first meets the medium without walking to it
// (render/first_medium.h).
#pragma once

#include "render/render_volume.h"

#include <vector>

namespace lh {

// Appends to `boxes` every stored brick's box of occupied cells in scene units (world frame),
// widened by a millionth of a voxel so that rounding cannot cut medium off, less the parts a
// finer level's domain covers (a box a domain spans along two axes is cut along the third;
// other overlaps keep it whole: a bound, not the field). False, with nothing appended, if a
// level holding medium is not axis-aligned (its boxes are not boxes in the world).
bool boundMedium(const std::vector<RenderLevel>& levels, std::vector<MediumBox>& boxes);

}  // namespace lh
