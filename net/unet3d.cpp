#include "net/unet3d.h"

#include "net/fast_conv.h"

namespace lh::net {

namespace F = torch::nn::functional;

ChannelLayerNormImpl::ChannelLayerNormImpl(int channels) {
    gain = register_parameter("gain", torch::ones({channels}));
    bias = register_parameter("bias", torch::zeros({channels}));
}

torch::Tensor ChannelLayerNormImpl::forward(const torch::Tensor& x) {
    const auto dims = std::vector<int64_t>{1, 2, 3, 4};
    const auto mean = x.mean(dims, /*keepdim=*/true);
    const auto var = (x - mean).pow(2).mean(dims, true);
    const auto normalised = (x - mean) * torch::rsqrt(var + 1e-5);
    return normalised * gain.view({1, -1, 1, 1, 1}) + bias.view({1, -1, 1, 1, 1});
}

PreActConvImpl::PreActConvImpl(int in, int out, int stride) {
    norm = register_module("norm", ChannelLayerNorm(in));
    conv = register_module(
        "conv", torch::nn::Conv3d(torch::nn::Conv3dOptions(in, out, 3).stride(stride).padding(1)));
}

torch::Tensor PreActConvImpl::forward(const torch::Tensor& x) {
    return fastConvolution(torch::relu(norm(x)), conv->weight, conv->bias,
                           conv->options.stride()->at(0), 1);
}

ResidualPairImpl::ResidualPairImpl(int channels) {
    first = register_module("first", PreActConv(channels, channels, 1));
    second = register_module("second", PreActConv(channels, channels, 1));
}

torch::Tensor ResidualPairImpl::forward(const torch::Tensor& x) { return x + second(first(x)); }

UNet3dWidths unet3dWidths(int w) {
    return {{w, 2 * w, 4 * w, 8 * w, 16 * w}, {8 * w, 4 * w, 2 * w, 2 * w}};
}

UNet3dImpl::UNet3dImpl(int inChannels, int outChannels, int w) {
    stem = register_module(
        "stem", torch::nn::Conv3d(torch::nn::Conv3dOptions(inChannels, w, 3).padding(1)));
    const UNet3dWidths widths = unet3dWidths(w);
    const int* enc = widths.encoder;
    const int* dec = widths.decoder;
    encRes.push_back(register_module("enc_res0", ResidualPair(enc[0])));
    for (int s = 0; s < 4; ++s) {
        down.push_back(
            register_module("down" + std::to_string(s), PreActConv(enc[s], enc[s + 1], 2)));
        encRes.push_back(
            register_module("enc_res" + std::to_string(s + 1), ResidualPair(enc[s + 1])));
    }
    int below = enc[4];
    for (int s = 0; s < 4; ++s) {
        const int skip = enc[3 - s];
        merge.push_back(
            register_module("merge" + std::to_string(s), PreActConv(below + skip, dec[s], 1)));
        decRes.push_back(register_module("dec_res" + std::to_string(s), ResidualPair(dec[s])));
        below = dec[s];
    }
    head = register_module("head", PreActConv(below, outChannels, 1));
}

torch::Tensor UNet3dImpl::forward(const torch::Tensor& x) {
    std::vector<torch::Tensor> skips;
    auto h = encRes[0](fastConvolution(x, stem->weight, stem->bias, 1, 1));
    for (int s = 0; s < 4; ++s) {
        skips.push_back(h);
        h = encRes[s + 1](down[s](h));
    }
    for (int s = 0; s < 4; ++s) {
        const auto& skip = skips[3 - s];
        // Nearest-neighbour 2x upsampling, sized to the skip exactly.
        h = F::interpolate(h,
                           F::InterpolateFuncOptions()
                               .size(std::vector<int64_t>{skip.size(2), skip.size(3), skip.size(4)})
                               .mode(torch::kNearest));
        h = decRes[s](merge[s](torch::cat({h, skip}, 1)));
    }
    return head(h);
}

}  // namespace lh::net
