#include "net/tensor_image.h"

#include "core/errors.h"
#include "image/luminance.h"

namespace lh::net {

torch::Tensor imageToTensor(const ImageRGB& image) {
    auto t = torch::from_blob(const_cast<float*>(image.pixels.data()),
                              {image.height, image.width, 3}, torch::kFloat32)
                 .clone();
    return t.permute({2, 0, 1}).unsqueeze(0).contiguous();
}

ImageRGB tensorToImage(const torch::Tensor& t) {
    if (t.dim() != 4 || t.size(0) != 1 || t.size(1) != 3)
        throw InputError("tensorToImage expects [1, 3, H, W]");
    const auto hwc =
        t.detach().to(torch::kCPU, torch::kFloat32).squeeze(0).permute({1, 2, 0}).contiguous();
    ImageRGB image(int(hwc.size(1)), int(hwc.size(0)));
    std::memcpy(image.pixels.data(), hwc.data_ptr<float>(), image.pixels.size() * sizeof(float));
    return image;
}

torch::Tensor luminanceTensor(const torch::Tensor& linear) {
    return kLumaR * linear.narrow(1, 0, 1) + kLumaG * linear.narrow(1, 1, 1) +
           kLumaB * linear.narrow(1, 2, 1);
}

torch::Tensor srgbEncodeTensor(const torch::Tensor& linear) {
    const auto x = linear.clamp(0.0, 1.0);
    // Piecewise sRGB curve; the offset inside the power keeps its derivative finite at 0.
    const auto curve = 1.055 * torch::pow(x + 1e-6, 1.0 / 2.4) - 0.055;
    return torch::where(x <= 0.0031308, 12.92 * x, curve);
}

torch::Tensor rotationTensor(const PinholeCamera& camera) {
    auto r = torch::empty({3, 3}, torch::kFloat64);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r[i][j] = camera.rotation(i, j);
    return r;
}

torch::Tensor positionTensor(const PinholeCamera& camera) {
    return torch::tensor({camera.position.x(), camera.position.y(), camera.position.z()},
                         torch::kFloat64);
}

torch::Tensor pixelRaysCamera(const PinholeCamera& camera) {
    const auto opts = torch::TensorOptions().dtype(torch::kFloat64);
    const auto u = (torch::arange(camera.width, opts) + 0.5 - camera.cx) / camera.fx;
    const auto v = (torch::arange(camera.height, opts) + 0.5 - camera.cy) / camera.fy;
    const auto grids = torch::meshgrid({v, u}, "ij");
    return torch::stack({grids[1], grids[0], torch::ones_like(grids[0])}, -1);  // z = 1, not unit
}

}  // namespace lh::net
