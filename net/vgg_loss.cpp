#include "net/vgg_loss.h"

#include "core/errors.h"
#include "net/tensor_image.h"

#include <torch/script.h>

#include <filesystem>
#include <map>

namespace lh::net {

namespace F = torch::nn::functional;

const int VggPerceptualLoss::kConvIndices[16] = {0,  2,  5,  7,  10, 12, 14, 16,
                                                 19, 21, 23, 25, 28, 30, 32, 34};

namespace {

constexpr int kWidths[16] = {64,  64,  128, 128, 256, 256, 256, 256,
                             512, 512, 512, 512, 512, 512, 512, 512};
// Max-pooling follows these convolutions (torchvision's layout).
bool poolAfter(int conv) { return conv == 1 || conv == 3 || conv == 7 || conv == 11; }
// Features taken after these convolutions' ReLU: conv1_2, conv2_2, conv3_2, conv4_2, conv5_2.
constexpr int kTaps[5] = {1, 3, 5, 9, 13};
// The authors' per-term weights: pixels, then the five layers.
constexpr double kTermWeights[6] = {1.0, 1.0 / 2.6, 1.0 / 4.8, 1.0 / 3.7, 1.0 / 5.6, 10.0 / 1.5};

}  // namespace

VggPerceptualLoss::VggPerceptualLoss(const std::string& path, const torch::Device& device) {
    if (!std::filesystem::is_regular_file(path))
        throw FileError("VGG-19 weights '" + path +
                        "' not found (see net/vgg_loss.h for how to make the file)");
    torch::jit::Module archive;
    try {
        archive = torch::jit::load(path, torch::kCPU);
    } catch (const c10::Error& e) {
        throw FileError("'" + path + "' is not a TorchScript archive of VGG-19 weights: " +
                        std::string(e.what_without_backtrace()).substr(0, 200));
    }
    std::map<std::string, torch::Tensor> buffers;
    for (const auto& b : archive.named_buffers(/*recurse=*/false)) buffers[b.name] = b.value;
    int in = 3;
    for (int c = 0; c < 16; ++c) {
        const std::string stem = std::to_string(kConvIndices[c]);
        const auto w = buffers.find(stem + "_weight"), b = buffers.find(stem + "_bias");
        if (w == buffers.end() || b == buffers.end())
            throw FileError("'" + path + "' lacks buffer " + stem + "_weight or " + stem +
                            "_bias of VGG-19's features");
        if (w->second.sizes() != torch::IntArrayRef({kWidths[c], in, 3, 3}))
            throw FileError("'" + path + "': buffer " + stem +
                            "_weight has the wrong shape for VGG-19");
        weights_.push_back(w->second.to(device, torch::kFloat32));
        biases_.push_back(b->second.to(device, torch::kFloat32));
        in = kWidths[c];
    }
    mean_ = torch::tensor({0.485f, 0.456f, 0.406f}).view({1, 3, 1, 1}).to(device);
    std_ = torch::tensor({0.229f, 0.224f, 0.225f}).view({1, 3, 1, 1}).to(device);
}

torch::Tensor VggPerceptualLoss::operator()(const torch::Tensor& predictedLinear,
                                            const torch::Tensor& targetLinear) const {
    const auto p = srgbEncodeTensor(predictedLinear), t = srgbEncodeTensor(targetLinear);
    auto loss = kTermWeights[0] * (p - t).abs().mean();
    auto hp = (p - mean_) / std_, ht = ((t - mean_) / std_).detach();
    int tap = 0;
    for (int c = 0; c < 16 && tap < 5; ++c) {
        const auto conv = [&](const torch::Tensor& x) {
            return torch::relu(
                F::conv2d(x, weights_[size_t(c)],
                          F::Conv2dFuncOptions().bias(biases_[size_t(c)]).padding(1)));
        };
        hp = conv(hp);
        ht = conv(ht);
        if (c == kTaps[tap]) {
            loss = loss + kTermWeights[tap + 1] * (hp - ht).abs().mean();
            ++tap;
        }
        if (poolAfter(c) && hp.size(2) >= 2 && hp.size(3) >= 2) {
            hp = F::max_pool2d(hp, F::MaxPool2dFuncOptions(2));
            ht = F::max_pool2d(ht, F::MaxPool2dFuncOptions(2));
        }
    }
    return loss;
}

}  // namespace lh::net
