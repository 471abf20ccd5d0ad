// Resampling a picture to another size: every network input and every contact-sheet tile
// passes through it.
#pragma once

#include "image/image.h"

namespace lh {

// Resamples an image to `width` x `height` by area averaging: each target pixel is the mean
// of the source area under it (partial pixels weighted by their overlap), so shrinking
// averages and growing repeats pixels.
ImageRGB resizeImage(const ImageRGB& image, int width, int height);

}  // namespace lh
