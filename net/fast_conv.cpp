#include "net/fast_conv.h"

#include <atomic>

namespace lh::net {

namespace {
std::atomic<bool> useOneDnn{true};
}

bool oneDnnConvolutionEnabled() { return useOneDnn && at::hasMKLDNN(); }
void setOneDnnConvolution(bool enabled) { useOneDnn = enabled; }

torch::Tensor fastConvolution(const torch::Tensor& x, const torch::Tensor& weight, const torch::Tensor& bias,
                              int64_t stride, int64_t padding) {
    const int64_t spatial = x.dim() - 2;
    const std::vector<int64_t> strides(size_t(spatial), stride), paddings(size_t(spatial), padding),
        dilations(size_t(spatial), 1);
    if (x.device().is_cpu() && x.scalar_type() == torch::kFloat32 && oneDnnConvolutionEnabled())
        return torch::mkldnn_convolution(x.contiguous(), weight, bias, paddings, strides, dilations, 1);
    if (spatial == 3) return torch::conv3d(x, weight, bias, strides, paddings);
    return torch::conv2d(x, weight, bias, strides, paddings);
}

}  // namespace lh::net
