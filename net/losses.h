// Training losses (SPEC.md step 8).
//  - imageLoss: L1 on sRGB-encoded clamp(linear, 0, 1) (the space the PSNR metric uses) plus
//    L1 on image gradients at two scales. This is our documented substitute for the VGG-19
//    perceptual loss, whose weights we cannot download here.
//  - PatchGAN discriminator: 4x4 convolutions 64-128-256-512-1, leaky ReLU 0.2, spectral
//    normalisation on every convolution; hinge loss.
#pragma once

#include "net/torch_pch.h"

namespace lh::net {

torch::Tensor imageLoss(const torch::Tensor& predictedLinear, const torch::Tensor& targetLinear);

// A 4x4 convolution whose weight is divided by its largest singular value, estimated by one
// power iteration per training forward pass (Miyato et al. 2018).
struct SpectralConv2dImpl : torch::nn::Module {
    SpectralConv2dImpl(int in, int out, int stride);
    torch::Tensor forward(const torch::Tensor& x);
    torch::Tensor weight, bias, u;  // u: the power iteration's left singular vector (a buffer)
    int stride;
};
TORCH_MODULE(SpectralConv2d);

struct PatchDiscriminatorImpl : torch::nn::Module {
    PatchDiscriminatorImpl();
    // [N, 3, H, W] sRGB-encoded images in [0, 1] -> patch scores [N, 1, h, w].
    torch::Tensor forward(const torch::Tensor& x);
    std::vector<SpectralConv2d> layers;
};
TORCH_MODULE(PatchDiscriminator);

// Hinge losses: the discriminator's on real and fake scores, and the generator's.
torch::Tensor discriminatorHingeLoss(const torch::Tensor& realScores, const torch::Tensor& fakeScores);
torch::Tensor generatorHingeLoss(const torch::Tensor& fakeScores);

// Sets non-finite gradient entries to zero (the paper's NaN guard) and returns how many were.
int64_t zeroNonFiniteGradients(const std::vector<torch::Tensor>& parameters);

}  // namespace lh::net
