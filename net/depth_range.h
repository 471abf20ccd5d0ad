// The scene's depth range seen by the reference camera, estimated from the stereo pair alone
// (the authors' code reads it from ground-truth depth; we do not need any).
//
// A plane sweep with photo-consistency: the source image is warped onto candidate planes of
// the reference camera (linear in disparity from 0.2 to 100 scene units), each pixel keeps
// the plane where a 7x7 window of the two images agrees best, and only textured pixels with a
// clear winner (best cost under 0.3 x the mean over the candidates whose window stays in the
// source image) vote. near / far are the 3rd and 97th percentiles of the votes, widened by 10%.
#pragma once

#include "core/camera.h"
#include "image/image.h"

#include <string>

namespace lh::net {

struct DepthRange {
    double near = 0, far = 0;  // scene units
    int votes = 0;             // pixels that voted
    bool fallback = false;     // too few votes: the documented default range was used
};

// Default range when the pair cannot tell (textureless or saturated images): a room.
constexpr double kFallbackNear = 0.5, kFallbackFar = 10.0;

DepthRange estimateDepthRange(const ImageRGB& ref, const ImageRGB& src,
                              const PinholeCamera& refCamera, const PinholeCamera& srcCamera);

}  // namespace lh::net
