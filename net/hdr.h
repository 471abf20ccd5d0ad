// HDR radiance from network outputs, and the encodings that feed radiance back into networks.
//
// Rooms' lamps and windows reach tens to thousands in linear radiance while walls sit near
// 0.1-1, so a sigmoid (radiance in [0, 1]) cannot represent them. The HDR activation is
// exp(x), with x clamped to [kMinLogRadiance, kMaxLogRadiance]: positive, unbounded in
// practice (up to e^9 = 8103), finite, and with the same relative resolution at every
// brightness, as the log-space losses expect. The clamp is soft (softplus at both ends), so
// the gradient never vanishes.
#pragma once

#include "net/torch_pch.h"

namespace lh::net {

constexpr double kMinLogRadiance = -12.0;  // e^-12 = 6e-6: black
constexpr double kMaxLogRadiance = 9.0;    // e^9 = 8103: brighter than any lamp we train on

// exp(softclamp(x, min, max)): HDR radiance from a logit.
torch::Tensor hdrActivation(const torch::Tensor& x);

// Where a photo clipped: 0 below linear 0.9 (sRGB 0.955) in every channel, 1 at 1, linear in
// between, per pixel from the brightest channel: [N, 3, H, W] -> [N, 1, H, W].
torch::Tensor saturationWeight(const torch::Tensor& linear);

// Radiance as a network input feature: ln(1 + x), so that a lamp of 500 is 6.2, not 500.
torch::Tensor radianceFeature(const torch::Tensor& linear);

}  // namespace lh::net
