// Contact sheets: rows of pictures scaled to a common height, for people to look at data
// sets and results at a glance.
#pragma once

#include "image/image.h"

#include <vector>

namespace lh {

// Each row's images, scaled to `tileHeight` pixels (aspect kept), side by side with a
// `gap`-pixel dark border; rows stacked top to bottom.
ImageRGB contactSheet(const std::vector<std::vector<ImageRGB>>& rows, int tileHeight, int gap = 4);

}  // namespace lh
