// Conversions between the project's types (ImageRGB, cameras) and tensors, and the colour
// encodings the networks and losses use. Tensors are float32, [N, C, H, W].
#pragma once

#include "core/camera.h"
#include "image/image.h"
#include "net/torch_pch.h"

namespace lh::net {

torch::Tensor imageToTensor(const ImageRGB& image);  // linear [1, 3, H, W]
ImageRGB tensorToImage(const torch::Tensor& t);      // [1, 3, H, W] (any device)

// sRGB encoding of clamp(linear, 0, 1), differentiable (a small offset keeps the gradient
// of the power law finite at 0). Network inputs and image losses live in this space.
torch::Tensor srgbEncodeTensor(const torch::Tensor& linear);

// Relative luminance Y (image/luminance.h's weights) of linear RGB in channels 0-2:
// [N, 3, ...] -> [N, 1, ...].
torch::Tensor luminanceTensor(const torch::Tensor& linear);

// Camera -> world rotation [3, 3] and centre [3], float64 on the CPU.
torch::Tensor rotationTensor(const PinholeCamera& camera);
torch::Tensor positionTensor(const PinholeCamera& camera);

// Unit ray directions (camera frame) through every pixel centre: [H, W, 3], float64.
torch::Tensor pixelRaysCamera(const PinholeCamera& camera);

// Continuous pixel coordinates -> grid_sample coordinates in [-1, 1] (align_corners = false).
inline torch::Tensor toGridCoordinate(const torch::Tensor& pixels, double size) {
    return pixels * (2.0 / size) - 1.0;
}

}  // namespace lh::net
