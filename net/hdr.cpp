#include "net/hdr.h"

namespace lh::net {

torch::Tensor hdrActivation(const torch::Tensor& x) {
    // A soft clamp: a hard one would stop the gradient of a colour that ran past a bound, and
    // a colour stuck there cannot come back.
    namespace F = torch::nn::functional;
    const auto above = kMinLogRadiance + F::softplus(x - kMinLogRadiance);
    return torch::exp(kMaxLogRadiance - F::softplus(kMaxLogRadiance - above));
}

torch::Tensor saturationWeight(const torch::Tensor& linear) {
    const auto brightest = std::get<0>(linear.max(1, /*keepdim=*/true));
    return ((brightest - 0.9) / 0.1).clamp(0.0, 1.0);
}

torch::Tensor radianceFeature(const torch::Tensor& linear) {
    return torch::log1p(linear.clamp_min(0.0));
}

}  // namespace lh::net
