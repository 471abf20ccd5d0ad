// Leaving over-exposed scenes out of training.
//
// A camera meters a room so that few pixels clip, and so do the path-traced evaluation rooms
// (dev_cycles): at most 10% of any envmap's pixels lie above 1 there, 3% on average. Our
// generator meters the reference photo only, and a point elsewhere in the room can see a
// sunlit wall or a white ceiling beside a lamp: 13% of its training envmaps clip on more than
// a tenth of their pixels, some on half. Trained on those, the model learnt to paint unseen
// content bright. train --max-clipped leaves such scenes out (docs/network.md).
#pragma once

#include "image/image.h"

#include <ostream>
#include <string>
#include <vector>

namespace lh::net {

// Fraction of the pixels whose mean of R, G and B is above 1 (linear): what a display shows
// as white. 0 for an empty image.
double clippedFraction(const ImageRGB& envmap);

// The example directories whose every ground-truth envmap (cameras.json's envmaps) has a
// clipped fraction of at most `maxClipped`, in their order. Reads every envmap, with a line on
// `progress` every 500 examples. Throws FileError for an unreadable example.
std::vector<std::string> withoutOverexposedScenes(const std::vector<std::string>& directories,
                                                  double maxClipped, std::ostream& progress);

}  // namespace lh::net
