// A 2D encoder-decoder for the MPI network of the `standard` configuration: its input
// channels are the plane-sweep volume's planes stacked (net/lighthouse_net.cpp says which),
// its outputs per-plane alpha and blend weights. Shape as net/unet3d.h (four stride-2 stages,
// residual pairs, nearest upsampling, skip concatenation, pre-activated convolutions) with
// widths w, 2w, 4w, 8w, 8w, and group norm with one group (layer norm over C, H, W).
#pragma once

#include "net/torch_pch.h"

namespace lh::net {

// conv(relu(groupnorm(x))), 3x3, padding 1.
struct PreActConv2dImpl : torch::nn::Module {
    PreActConv2dImpl(int in, int out, int stride);
    torch::Tensor forward(const torch::Tensor& x);
    torch::nn::GroupNorm norm{nullptr};
    torch::nn::Conv2d conv{nullptr};
    int stride;
};
TORCH_MODULE(PreActConv2d);

struct UNet2dImpl : torch::nn::Module {
    UNet2dImpl(int inChannels, int outChannels, int baseWidth);
    // x: [N, inChannels, H, W] with H, W multiples of 16 -> [N, outChannels, H, W].
    torch::Tensor forward(const torch::Tensor& x);

    torch::nn::Conv2d stem{nullptr};
    std::vector<PreActConv2d> down, encRes, merge, decRes;
    PreActConv2d head{nullptr};
};
TORCH_MODULE(UNet2d);

}  // namespace lh::net
