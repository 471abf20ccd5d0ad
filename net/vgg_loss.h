// The paper's perceptual loss: L1 distances between VGG-19 features of the prediction and the
// target (pixels, conv1_2, conv2_2, conv3_2, conv4_2, conv5_2, each after its ReLU), with the
// per-layer weights of the authors' code. Used by `train --vgg FILE` when the user supplies
// the ImageNet weights; otherwise training uses the substitute in losses.h.
//
// FILE is a TorchScript archive whose buffers are torchvision's `vgg19().features` state dict
// with '.' replaced by '_' ("0_weight", "0_bias", "2_weight", ..., "34_bias"). Make it once,
// where torchvision can download the weights:
//
//   import torch, torchvision
//   sd = torchvision.models.vgg19(weights="IMAGENET1K_V1").features.state_dict()
//   class Weights(torch.nn.Module):
//       def __init__(self):
//           super().__init__()
//           for k, v in sd.items(): self.register_buffer(k.replace(".", "_"), v)
//   torch.jit.save(torch.jit.script(Weights()), "vgg19_features.pt")
#pragma once

#include "net/torch_pch.h"

#include <string>

namespace lh::net {

class VggPerceptualLoss {
public:
    // Throws FileError naming the file and the missing or mis-shaped buffer.
    VggPerceptualLoss(const std::string& weightsPath, const torch::Device& device);
    // Linear images [1, 3, H, W] (compared after sRGB encoding and ImageNet normalisation).
    torch::Tensor operator()(const torch::Tensor& predictedLinear,
                             const torch::Tensor& targetLinear) const;

    // torchvision's layer indices of the 16 convolutions of vgg19().features.
    static const int kConvIndices[16];

private:
    std::vector<torch::Tensor> weights_, biases_;  // frozen, 16 convolutions
    torch::Tensor mean_, std_;
};

}  // namespace lh::net
