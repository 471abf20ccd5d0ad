// The plane-sweep volume (docs/method.md#plane-sweep-volume): the source image warped onto
// fronto-parallel planes of the reference camera by the plane-induced homography, bilinear, zero
// outside the image.
#pragma once

#include "core/camera.h"
#include "net/torch_pch.h"

#include <vector>

namespace lh::net {

// Grid_sample coordinates [D, H, W, 2] that map reference pixel (u, v) on the plane at
// depth `depths[d]` (reference camera frame) to the pixel of `other` that sees the same point.
// Points behind `other` map outside the image (sampled as zero).
torch::Tensor planeWarpGrid(const PinholeCamera& ref, const PinholeCamera& other,
                            const std::vector<double>& depths);

// [1, 6, D, H, W]: per plane, the reference image and the warped source image (both as given,
// [1, 3, H, W] and [1, 3, Hs, Ws]; the pipeline passes sRGB-encoded values in [0, 1]).
torch::Tensor planeSweepVolume(const torch::Tensor& refImage, const torch::Tensor& srcImage,
                               const PinholeCamera& ref, const PinholeCamera& src,
                               const std::vector<double>& depths);

}  // namespace lh::net
