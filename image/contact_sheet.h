// Contact sheets: rows of pictures scaled to a common height, for people to look at data
// sets and results at a glance.
#pragma once

#include "image/image.h"

#include <vector>

namespace lh {

// Resamples an image to `width` x `height` by area averaging: each target pixel is the mean
// of the source area under it (partial pixels weighted by their overlap), so shrinking
// averages and growing repeats pixels. Every network input passes through it.
ImageRGB resizeImage(const ImageRGB& image, int width, int height);

// Each row's images, scaled to `tileHeight` pixels (aspect kept), side by side with a
// `gap`-pixel dark border; rows stacked top to bottom.
ImageRGB contactSheet(const std::vector<std::vector<ImageRGB>>& rows, int tileHeight, int gap = 4);

}  // namespace lh
