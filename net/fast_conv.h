// Convolutions that take oneDNN's kernels on the CPU whatever the input size.
//
// Debian's libtorch is built with oneDNN (MKL-DNN), but torch::conv2d / conv3d only choose it
// when N x C x D x H exceeds 20480, so at batch 1 with few channels they fall back to the
// native im2col kernel. torch::mkldnn_convolution is differentiable and always uses oneDNN:
// on this project's 2-core machine it made a 3D convolution's forward + backward 2.4-2.9x
// faster (bench/net_step_bench.cpp measures the training step per stage). On other devices
// (CUDA) the ordinary convolution runs.
#pragma once

#include "net/torch_pch.h"

namespace lh::net {

// x: [N, C, (D,) H, W]; weight: [out, C, k, k(, k)]; same padding and stride on every axis.
torch::Tensor fastConvolution(const torch::Tensor& x, const torch::Tensor& weight,
                              const torch::Tensor& bias, int64_t stride, int64_t padding);

// Whether fastConvolution uses oneDNN on the CPU (where libtorch has it; on by default). The
// training-step profile turns it off to measure what it saves.
bool oneDnnConvolutionEnabled();
void setOneDnnConvolution(bool enabled);

}  // namespace lh::net
