#include "net/losses.h"

#include "net/tensor_image.h"

namespace lh::net {

namespace F = torch::nn::functional;

namespace {

torch::Tensor gradientL1(const torch::Tensor& a, const torch::Tensor& b) {
    const auto dx = [](const torch::Tensor& t) { return t.narrow(3, 1, t.size(3) - 1) - t.narrow(3, 0, t.size(3) - 1); };
    const auto dy = [](const torch::Tensor& t) { return t.narrow(2, 1, t.size(2) - 1) - t.narrow(2, 0, t.size(2) - 1); };
    return (dx(a) - dx(b)).abs().mean() + (dy(a) - dy(b)).abs().mean();
}

}  // namespace

torch::Tensor imageLoss(const torch::Tensor& predictedLinear, const torch::Tensor& targetLinear) {
    const auto p = srgbEncodeTensor(predictedLinear), t = srgbEncodeTensor(targetLinear);
    auto loss = (p - t).abs().mean() + gradientL1(p, t);
    if (p.size(2) >= 8 && p.size(3) >= 8) {
        const auto pooledP = F::avg_pool2d(p, F::AvgPool2dFuncOptions(2));
        const auto pooledT = F::avg_pool2d(t, F::AvgPool2dFuncOptions(2));
        loss = loss + gradientL1(pooledP, pooledT);
    }
    return loss;
}

SpectralConv2dImpl::SpectralConv2dImpl(int in, int out, int s) : stride(s) {
    weight = register_parameter("weight", torch::randn({out, in, 4, 4}) * std::sqrt(2.0 / (in * 16)));
    bias = register_parameter("bias", torch::zeros({out}));
    u = register_buffer("u", F::normalize(torch::randn({out}), F::NormalizeFuncOptions().dim(0)));
}

torch::Tensor SpectralConv2dImpl::forward(const torch::Tensor& x) {
    const auto matrix = weight.view({weight.size(0), -1});
    if (is_training()) {
        torch::NoGradGuard noGrad;
        const auto v = F::normalize(torch::mv(matrix.t(), u), F::NormalizeFuncOptions().dim(0));
        u.copy_(F::normalize(torch::mv(matrix, v), F::NormalizeFuncOptions().dim(0)));
    }
    // A copy of u: the next training forward pass updates the buffer in place, and this pass's
    // graph must keep the value it used.
    const auto uNow = u.detach().clone();
    const auto v = F::normalize(torch::mv(matrix.t(), uNow), F::NormalizeFuncOptions().dim(0)).detach();
    const auto sigma = torch::dot(uNow, torch::mv(matrix, v));
    return F::conv2d(x, weight / sigma, F::Conv2dFuncOptions().bias(bias).stride(stride).padding(1));
}

PatchDiscriminatorImpl::PatchDiscriminatorImpl() {
    const int widths[6] = {3, 64, 128, 256, 512, 1};
    const int strides[5] = {2, 2, 2, 1, 1};
    for (int i = 0; i < 5; ++i)
        layers.push_back(register_module("conv" + std::to_string(i),
                                         SpectralConv2d(widths[i], widths[i + 1], strides[i])));
}

torch::Tensor PatchDiscriminatorImpl::forward(const torch::Tensor& x) {
    auto h = x;
    for (size_t i = 0; i < layers.size(); ++i) {
        h = layers[i](h);
        if (i + 1 < layers.size()) h = F::leaky_relu(h, F::LeakyReLUFuncOptions().negative_slope(0.2));
    }
    return h;
}

torch::Tensor discriminatorHingeLoss(const torch::Tensor& real, const torch::Tensor& fake) {
    return torch::relu(1.0 - real).mean() + torch::relu(1.0 + fake).mean();
}

torch::Tensor generatorHingeLoss(const torch::Tensor& fake) { return -fake.mean(); }

int64_t zeroNonFiniteGradients(const std::vector<torch::Tensor>& parameters) {
    int64_t count = 0;
    for (const auto& p : parameters) {
        if (!p.grad().defined()) continue;
        auto g = p.mutable_grad();
        const auto bad = ~torch::isfinite(g);
        const int64_t n = bad.sum().item<int64_t>();
        if (n > 0) {
            g.masked_fill_(bad, 0.0);
            count += n;
        }
    }
    return count;
}

}  // namespace lh::net
