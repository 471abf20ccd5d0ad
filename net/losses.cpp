#include "net/losses.h"

#include "image/irradiance_weights.h"
#include "image/luminance.h"
#include "net/tensor_image.h"
#include "net/volume_render.h"

#include <cmath>

namespace lh::net {

namespace F = torch::nn::functional;

namespace {

torch::Tensor gradientL1(const torch::Tensor& a, const torch::Tensor& b) {
    const auto dx = [](const torch::Tensor& t) {
        return t.narrow(3, 1, t.size(3) - 1) - t.narrow(3, 0, t.size(3) - 1);
    };
    const auto dy = [](const torch::Tensor& t) {
        return t.narrow(2, 1, t.size(2) - 1) - t.narrow(2, 0, t.size(2) - 1);
    };
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

torch::Tensor squaredImageLoss(const torch::Tensor& predictedLinear,
                               const torch::Tensor& targetLinear) {
    return (srgbEncodeTensor(predictedLinear) - srgbEncodeTensor(targetLinear)).square().mean();
}

SpectralConv2dImpl::SpectralConv2dImpl(int in, int out, int s) : stride(s) {
    weight =
        register_parameter("weight", torch::randn({out, in, 4, 4}) * std::sqrt(2.0 / (in * 16)));
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
    const auto v =
        F::normalize(torch::mv(matrix.t(), uNow), F::NormalizeFuncOptions().dim(0)).detach();
    const auto sigma = torch::dot(uNow, torch::mv(matrix, v));
    return F::conv2d(x, weight / sigma,
                     F::Conv2dFuncOptions().bias(bias).stride(stride).padding(1));
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
        if (i + 1 < layers.size())
            h = F::leaky_relu(h, F::LeakyReLUFuncOptions().negative_slope(0.2));
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

namespace lh::net {

torch::Tensor hdrImageLoss(const torch::Tensor& predicted, const torch::Tensor& target) {
    return (torch::log1p(predicted.clamp_min(0.0)) - torch::log1p(target.clamp_min(0.0)))
        .abs()
        .mean();
}

torch::Tensor coarseHdrImageLoss(const torch::Tensor& predicted, const torch::Tensor& target,
                                 int block) {
    if (block <= 1) return hdrImageLoss(predicted, target);
    block = int(std::min<int64_t>({int64_t(block), predicted.size(-2), predicted.size(-1)}));
    return hdrImageLoss(torch::avg_pool2d(predicted.clamp_min(0.0), {block, block}),
                        torch::avg_pool2d(target.clamp_min(0.0), {block, block}));
}

torch::Tensor highlightLoss(const torch::Tensor& predicted, const torch::Tensor& target,
                            const torch::Tensor& observed) {
    const auto yPred = luminanceTensor(predicted).clamp_min(0.0);
    const auto yTrue = luminanceTensor(target).clamp_min(0.0);
    const auto trueHighlight = yTrue > kLampLuminance;
    const auto show =
        torch::relu(torch::log1p(yTrue.clamp_max(2.0 * kLampLuminance)) - torch::log1p(yPred));
    const auto hide = torch::relu(torch::log1p(yPred) - std::log1p(kLampLuminance));
    // Every pixel pays for its own term: a lamp pixel left dim and a wall pixel shown as a
    // highlight cost alike, so the light a lamp spills onto its neighbours is charged too.
    return (show * (trueHighlight & (observed != 0)).to(show.dtype()) +
            hide * trueHighlight.logical_not().to(hide.dtype()))
        .mean();
}

torch::Tensor logRadianceEncode(const torch::Tensor& linear) {
    return torch::log1p(linear.clamp_min(0.0)) / std::log1p(kAdversarialLogPeak);
}

torch::Tensor axisIrradianceTensor(const torch::Tensor& envmaps) {
    const int64_t n = envmaps.size(0), h = envmaps.size(2), w = envmaps.size(3);
    // [P, 6]: max(0, n . d) dOmega, the metric's own table (image/irradiance_weights.h).
    std::vector<double> table = axisIrradianceWeights(int(w), int(h));
    const auto weights =
        torch::from_blob(table.data(), {h * w, int64_t(kAxisNormals)}, torch::kFloat64)
            .to(envmaps.device(), envmaps.scalar_type(), /*non_blocking=*/false,
                /*copy=*/true);  // owns its memory: `table` dies here
    return torch::matmul(envmaps.reshape({n, 3, h * w}), weights);
}

torch::Tensor irradianceLoss(const torch::Tensor& predicted, const torch::Tensor& target) {
    const auto ep = axisIrradianceTensor(predicted.clamp_min(0.0));
    const auto et = axisIrradianceTensor(target.clamp_min(0.0));
    const auto floor = 1e-3 * et.mean() + 1e-12;
    return ((ep - et).abs() / (et + floor)).mean();
}

torch::Tensor focusedIrradianceLoss(const torch::Tensor& predicted, const torch::Tensor& target,
                                    double focus) {
    if (focus == 0.0) return irradianceLoss(predicted, target);
    const auto linear = predicted.clamp_min(0.0);
    const auto frozen = linear.detach();
    const auto luminance = luminanceTensor(frozen);  // [N, 1, H, W]
    // (Y / mean Y)^focus normalised to a mean of 1 is Y^focus over its mean.
    const auto weight = luminance.pow(focus);
    const auto share = weight / (weight.mean({2, 3}, true) + 1e-12);
    // The forward value is `linear`'s; the gradient reaching each pixel is scaled by its share.
    return irradianceLoss(frozen + share * (linear - frozen), target);
}

torch::Tensor voxelLoss(const std::vector<torch::Tensor>& predicted,
                        const std::vector<torch::Tensor>& target) {
    constexpr double kAlphaFloor = 1e-4, kCrossEntropyWeight = 0.1;
    auto total = torch::zeros({}, predicted.front().options());
    for (size_t k = 0; k < predicted.size(); ++k) {
        const auto pa = predicted[k].narrow(1, 3, 1), ta = target[k].narrow(1, 3, 1);
        const auto weight = 1.0 + 2.0 * ta;
        // L1 on alpha: its optimum where the room is uncertain (a wall that may be here or a
        // few voxels on) is the median, empty or opaque, not the mean, which is fog that hides
        // everything behind it. A tenth of the binary cross-entropy keeps a gradient through a
        // saturated sigmoid, so a surface voxel pushed towards 0 by the empty space around it
        // recovers.
        const auto pc = pa.clamp(kAlphaFloor, 1.0 - kAlphaFloor);
        const auto crossEntropy = -(ta * torch::log(pc) + (1.0 - ta) * torch::log1p(-pc));
        const auto alphaError = (pa - ta).abs() + kCrossEntropyWeight * crossEntropy;
        // Colour where the oracle has a surface, whatever the predicted alpha: a premultiplied
        // error would let a nearly transparent voxel chase the target with a huge colour.
        const auto radianceError = ta * (torch::log1p(predicted[k].narrow(1, 0, 3).clamp_min(0.0)) -
                                         torch::log1p(target[k].narrow(1, 0, 3)))
                                            .abs()
                                            .mean(1, true);
        total = total + ((alphaError + radianceError) * weight).sum() / weight.sum();
    }
    return total / double(predicted.size());
}

torch::Tensor closureLoss(const torch::Tensor& transmittance) { return transmittance.mean(); }

torch::Tensor mpiExpectedDisparity(const torch::Tensor& mpi, const std::vector<double>& depths) {
    const auto alpha = mpi.narrow(1, 3, 1).clamp(0.0, 1.0 - 1e-6);  // [1, 1, D, H, W]
    const auto logClear = torch::log1p(-alpha);
    // Transmittance in front of plane d: product of (1 - alpha) over the nearer planes d' > d.
    const auto nearer = logClear.flip(2).cumsum(2).flip(2) - logClear;
    const auto weights = torch::exp(nearer) * alpha;
    std::vector<float> disparity;
    for (double d : depths) disparity.push_back(float(1.0 / d));
    const auto disp = torch::tensor(disparity).to(mpi.device()).view({1, 1, -1, 1, 1});
    const auto remaining = torch::exp(logClear.sum(2));  // [1, 1, H, W]
    return (weights * disp).sum(2) + remaining * (1.0 / depths.front());
}

torch::Tensor mpiDepthLoss(const torch::Tensor& mpi, const std::vector<double>& depths,
                           const torch::Tensor& trueDepth) {
    const double range = 1.0 / depths.back() - 1.0 / depths.front();
    const auto truth = 1.0 / trueDepth.clamp_min(1e-3);
    return (mpiExpectedDisparity(mpi, depths) - truth).abs().mean() / range;
}

torch::Tensor sparsityLoss(const std::vector<torch::Tensor>& cubes) {
    auto total = torch::zeros({}, cubes.front().options());
    for (const auto& c : cubes) total = total + c.narrow(1, 3, 1).mean();
    return total / double(cubes.size());
}

torch::Tensor emitterPositionLoss(const torch::Tensor& lamps, const torch::Tensor& trueLamps) {
    const auto distance2 = (lamps.unsqueeze(1) - trueLamps.unsqueeze(0)).pow(2).sum(-1);  // [K, M]
    return std::get<0>(distance2.min(1)).mean();
}

torch::Tensor cellDivergence(const torch::Tensor& target, const torch::Tensor& logProbability) {
    // xlogy: 0 ln 0 = 0, and a cell without a lamp adds nothing whatever p is there, even a
    // masked one (p = 0, ln p = -inf, where 0 x -inf would be NaN).
    const auto crossTerm =
        torch::where(target > 0, target * logProbability, torch::zeros_like(logProbability));
    return (torch::xlogy(target, target) - crossTerm).sum(1);
}

torch::Tensor emitterCellLoss(const torch::Tensor& cellLogits, const torch::Tensor& target) {
    // ln of the mixture of the lamps' distributions, 1/K sum_k softmax_k, per cell.
    const auto logMixture =
        torch::log_softmax(cellLogits, 1).logsumexp(0) - std::log(double(cellLogits.size(0)));
    return cellDivergence(target.to(cellLogits.options()).unsqueeze(0), logMixture.unsqueeze(0))
        .squeeze(0);
}

torch::Tensor binaryAlphaLoss(const std::vector<torch::Tensor>& cubes) {
    auto total = torch::zeros({}, cubes.front().options());
    for (const auto& c : cubes) {
        const auto alpha = c.narrow(1, 3, 1);
        total = total + (alpha * (1 - alpha)).mean();
    }
    return total / double(cubes.size());
}

}  // namespace lh::net
