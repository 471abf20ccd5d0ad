// Where a photo clips, and how bright its clipped pixels truly are. A camera saves everything
// above 1 as 1; whether those pixels are lamps and windows (tens to hundreds) or bright walls
// (just above 1) decides how much a network should brighten them, so a training set whose
// clipped pixels are mostly walls teaches a network to leave clipped lamps dim. Both functions
// read unclipped radiance (a view's EXR), linear, as rendered.
#pragma once

#include "image/image.h"

#include <vector>

namespace lh {

// True luminance above which a clipped pixel counts as lamp- or window-bright: 8 times the
// display's white, between the walls that clip just above 1 and the lamps and windows (tens to
// hundreds).
constexpr double kLampBrightLuminance = 8.0;

// The largest exposure at which at most `maxFraction` (in [0, 1]) of `linear`'s pixels clip
// (some channel times exposure times `gain` above 1), as a camera that meters for its
// highlights chooses it; +infinity when the photo is that dark (those pixels are black).
double exposureClippingAtMost(const ImageRGB& linear, const double gain[3], double maxFraction);

// The luminances (Rec. 709, times `exposure`) of the pixels of `linear` that clip at
// `exposure` (some channel above 1), in pixel order.
std::vector<double> clippedLuminances(const ImageRGB& linear, double exposure);

}  // namespace lh
