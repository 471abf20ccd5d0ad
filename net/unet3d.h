// The 3D encoder-decoder of the paper's supplement (Table 1), used for the MPI network over
// (planes, rows, columns) and for every completion network over (z, y, x):
//   encoder widths w, 2w, 4w, 8w, 16w (w = 8 in the paper) with four stride-2 3x3x3
//   convolutions, each stage followed by a residual pair of 3x3x3 convolutions;
//   decoder 8w, 4w, 2w, 2w with 2x nearest-neighbour upsampling and skip concatenation;
//   every convolution is pre-activated: conv(relu(layernorm(x))).
#pragma once

#include "net/torch_pch.h"

namespace lh::net {

// Layer norm over all non-batch dimensions (C, D, H, W), per-channel gain and bias.
struct ChannelLayerNormImpl : torch::nn::Module {
    explicit ChannelLayerNormImpl(int channels);
    torch::Tensor forward(const torch::Tensor& x);
    torch::Tensor gain, bias;
};
TORCH_MODULE(ChannelLayerNorm);

// conv(relu(layernorm(x))), 3x3x3, padding 1.
struct PreActConvImpl : torch::nn::Module {
    PreActConvImpl(int in, int out, int stride);
    torch::Tensor forward(const torch::Tensor& x);
    ChannelLayerNorm norm{nullptr};
    torch::nn::Conv3d conv{nullptr};
};
TORCH_MODULE(PreActConv);

// x + conv(conv(x)), widths unchanged.
struct ResidualPairImpl : torch::nn::Module {
    explicit ResidualPairImpl(int channels);
    torch::Tensor forward(const torch::Tensor& x);
    PreActConv first{nullptr}, second{nullptr};
};
TORCH_MODULE(ResidualPair);

// Channels of each stage of a U-Net of base width w: the stem and the encoder stages after it
// (w .. 16 w), and the decoder stages after each merge (8 w .. 2 w). net/widen.cpp reads the
// same plan to map a network onto one twice as wide.
struct UNet3dWidths {
    int encoder[5];
    int decoder[4];
};
UNet3dWidths unet3dWidths(int baseWidth);

struct UNet3dImpl : torch::nn::Module {
    UNet3dImpl(int inChannels, int outChannels, int baseWidth);
    // x: [N, inChannels, D, H, W] with D, H, W multiples of 16 -> [N, outChannels, D, H, W].
    torch::Tensor forward(const torch::Tensor& x);

    torch::nn::Conv3d stem{nullptr};
    std::vector<PreActConv> down;      // 4 stride-2 convolutions
    std::vector<ResidualPair> encRes;  // 5: after the stem and after each down
    std::vector<PreActConv> merge;     // 4: after upsampling + skip concatenation
    std::vector<ResidualPair> decRes;  // 4
    PreActConv head{nullptr};
};
TORCH_MODULE(UNet3d);

}  // namespace lh::net
