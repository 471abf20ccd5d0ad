#include "net/fast_conv.h"

#include <atomic>

namespace lh::net {

namespace {

std::atomic<bool> useOneDnn{true};

std::vector<int64_t> repeated(int64_t spatial, int64_t value) {
    return std::vector<int64_t>(size_t(spatial), value);
}

torch::Tensor oneDnnForward(const torch::Tensor& x, const torch::Tensor& weight,
                            const torch::Tensor& bias, int64_t stride, int64_t padding) {
    const int64_t spatial = x.dim() - 2;
    return torch::mkldnn_convolution(x.contiguous(), weight.contiguous(), bias,
                                     repeated(spatial, padding), repeated(spatial, stride),
                                     repeated(spatial, 1), 1);
}

// The gradient with respect to the input: the output gradient spread back to the input's
// grid (zeros between its samples when the stride is 2), correlated with the kernel turned
// end for end and its in/out channels swapped. A stride-1 oneDNN convolution, as fast as the
// forward pass.
torch::Tensor inputGradient(const torch::Tensor& grad, const torch::Tensor& weight,
                            const at::IntArrayRef inputSize, int64_t stride, int64_t padding) {
    const int64_t spatial = grad.dim() - 2, kernel = weight.size(2);
    std::vector<int64_t> flipDims, spreadSize = {grad.size(0), grad.size(1)};
    for (int64_t d = 0; d < spatial; ++d) {
        flipDims.push_back(2 + d);
        spreadSize.push_back(inputSize[size_t(2 + d)] + 2 * padding - kernel + 1);
    }
    torch::Tensor spread = grad;
    if (stride != 1) {
        spread = torch::zeros(spreadSize, grad.options());
        torch::Tensor view = spread;
        for (int64_t d = 0; d < spatial; ++d)
            view = view.slice(2 + d, 0, stride * grad.size(2 + d), stride);
        view.copy_(grad);
    }
    const auto turned = weight.flip(flipDims).transpose(0, 1).contiguous();
    return torch::mkldnn_convolution(spread.contiguous(), turned, {},
                                     repeated(spatial, kernel - 1 - padding), repeated(spatial, 1),
                                     repeated(spatial, 1), 1);
}

// The gradient with respect to the weights: for every kernel offset, the output gradient
// times the input shifted by that offset, summed over positions and the batch. That is itself
// a convolution, with the roles swapped: the padded input's channels as the batch, the output
// gradient as the kernel (dilated by the stride). Copying the input's shifted windows out
// instead (im2col) cost 10x more here, most of it the kernel zeroing fresh pages.
torch::Tensor weightGradient(const torch::Tensor& grad, const torch::Tensor& x,
                             const at::IntArrayRef weightSize, int64_t stride, int64_t padding) {
    const int64_t spatial = x.dim() - 2, kernel = weightSize[2];
    std::vector<int64_t> pad;
    for (int64_t d = 0; d < spatial; ++d) pad.insert(pad.end(), {padding, padding});
    const auto input =
        torch::constant_pad_nd(x, pad, 0.0).transpose(0, 1).contiguous();  // [in, N, ...]
    const auto asKernel = grad.transpose(0, 1).contiguous();               // [out, N, ...]
    auto product =
        torch::mkldnn_convolution(input, asKernel, {}, repeated(spatial, 0), repeated(spatial, 1),
                                  repeated(spatial, stride), 1);  // [in, out, >= k...]
    for (int64_t d = 0; d < spatial; ++d) product = product.narrow(2 + d, 0, kernel);
    return product.transpose(0, 1).contiguous();
}

// oneDNN's own backward pass (through torch::mkldnn_convolution's autograd) runs 25-75x
// slower than its forward pass on this project's small 3D shapes (11 -> 4 channels over 32^3:
// 250 ms against 8 ms; bench/train_step_bench.cpp): the forward is oneDNN and the gradients
// are the two convolutions above.
struct OneDnnConvolution : torch::autograd::Function<OneDnnConvolution> {
    static torch::Tensor forward(torch::autograd::AutogradContext* ctx, const torch::Tensor& x,
                                 const torch::Tensor& weight, const torch::Tensor& bias,
                                 int64_t stride, int64_t padding) {
        ctx->save_for_backward({x, weight});
        ctx->saved_data["stride"] = stride;
        ctx->saved_data["padding"] = padding;
        return oneDnnForward(x, weight, bias, stride, padding);
    }

    static torch::autograd::variable_list backward(torch::autograd::AutogradContext* ctx,
                                                   torch::autograd::variable_list grads) {
        const auto saved = ctx->get_saved_variables();
        const auto &x = saved[0], &weight = saved[1];
        const int64_t stride = ctx->saved_data["stride"].toInt(),
                      padding = ctx->saved_data["padding"].toInt();
        const auto grad = grads[0].contiguous();
        torch::Tensor gx, gw, gb;
        if (ctx->needs_input_grad(0)) gx = inputGradient(grad, weight, x.sizes(), stride, padding);
        if (ctx->needs_input_grad(1)) gw = weightGradient(grad, x, weight.sizes(), stride, padding);
        if (ctx->needs_input_grad(2)) {
            std::vector<int64_t> dims = {0};
            for (int64_t d = 2; d < grad.dim(); ++d) dims.push_back(d);
            gb = grad.sum(dims);
        }
        return {gx, gw, gb, torch::Tensor(), torch::Tensor()};
    }
};

}  // namespace

bool oneDnnConvolutionEnabled() { return useOneDnn && at::hasMKLDNN(); }
void setOneDnnConvolution(bool enabled) { useOneDnn = enabled; }

torch::Tensor fastConvolution(const torch::Tensor& x, const torch::Tensor& weight,
                              const torch::Tensor& bias, int64_t stride, int64_t padding) {
    const int64_t spatial = x.dim() - 2;
    if (x.device().is_cpu() && x.scalar_type() == torch::kFloat32 && oneDnnConvolutionEnabled()) {
        // 2D: oneDNN's own backward pass is as fast as libtorch's native one.
        if (spatial != 3 || !torch::GradMode::is_enabled())
            return oneDnnForward(x, weight, bias, stride, padding);
        // A custom function's arguments must all be tensors: no bias is a zero bias.
        const auto b = bias.defined()
                           ? bias
                           : torch::zeros({weight.size(0)}, weight.options().requires_grad(false));
        return OneDnnConvolution::apply(x, weight, b, stride, padding);
    }
    const auto strides = repeated(spatial, stride), paddings = repeated(spatial, padding);
    if (spatial == 3) return torch::conv3d(x, weight, bias, strides, paddings);
    return torch::conv2d(x, weight, bias, strides, paddings);
}

}  // namespace lh::net
