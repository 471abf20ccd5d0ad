#include "net/unet2d.h"

#include "net/fast_conv.h"

namespace lh::net {

namespace F = torch::nn::functional;

PreActConv2dImpl::PreActConv2dImpl(int in, int out, int s) : stride(s) {
    norm = register_module("norm", torch::nn::GroupNorm(torch::nn::GroupNormOptions(1, in)));
    conv = register_module(
        "conv", torch::nn::Conv2d(torch::nn::Conv2dOptions(in, out, 3).stride(s).padding(1)));
}

torch::Tensor PreActConv2dImpl::forward(const torch::Tensor& x) {
    return fastConvolution(torch::relu(norm(x)), conv->weight, conv->bias, stride, 1);
}

UNet2dImpl::UNet2dImpl(int inChannels, int outChannels, int w) {
    stem = register_module(
        "stem", torch::nn::Conv2d(torch::nn::Conv2dOptions(inChannels, w, 3).padding(1)));
    const int enc[5] = {w, 2 * w, 4 * w, 8 * w, 8 * w};
    const int dec[4] = {8 * w, 4 * w, 2 * w, w};
    encRes.push_back(register_module("enc_res0", PreActConv2d(enc[0], enc[0], 1)));
    for (int s = 0; s < 4; ++s) {
        down.push_back(
            register_module("down" + std::to_string(s), PreActConv2d(enc[s], enc[s + 1], 2)));
        encRes.push_back(register_module("enc_res" + std::to_string(s + 1),
                                         PreActConv2d(enc[s + 1], enc[s + 1], 1)));
    }
    int below = enc[4];
    for (int s = 0; s < 4; ++s) {
        const int skip = enc[3 - s];
        merge.push_back(
            register_module("merge" + std::to_string(s), PreActConv2d(below + skip, dec[s], 1)));
        decRes.push_back(
            register_module("dec_res" + std::to_string(s), PreActConv2d(dec[s], dec[s], 1)));
        below = dec[s];
    }
    head = register_module("head", PreActConv2d(below, outChannels, 1));
}

torch::Tensor UNet2dImpl::forward(const torch::Tensor& x) {
    std::vector<torch::Tensor> skips;
    auto h = fastConvolution(x, stem->weight, stem->bias, 1, 1);
    h = h + encRes[0](h);
    for (int s = 0; s < 4; ++s) {
        skips.push_back(h);
        h = down[s](h);
        h = h + encRes[s + 1](h);
    }
    for (int s = 0; s < 4; ++s) {
        const auto& skip = skips[3 - s];
        h = F::interpolate(h, F::InterpolateFuncOptions()
                                  .size(std::vector<int64_t>{skip.size(2), skip.size(3)})
                                  .mode(torch::kNearest));
        h = merge[s](torch::cat({h, skip}, 1));
        h = h + decRes[s](h);
    }
    return head(h);
}

}  // namespace lh::net
