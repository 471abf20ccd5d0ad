#include "net/psv.h"

#include "net/tensor_image.h"

namespace lh::net {

namespace F = torch::nn::functional;

torch::Tensor planeWarpGrid(const PinholeCamera& ref, const PinholeCamera& other,
                            const std::vector<double>& depths) {
    const auto rays = pixelRaysCamera(ref);  // [H, W, 3], z = 1
    const auto depth = torch::tensor(depths, torch::kFloat64).view({-1, 1, 1, 1});
    const auto pointsRef = rays.unsqueeze(0) * depth;  // [D, H, W, 3], reference camera frame
    const auto world = torch::matmul(pointsRef, rotationTensor(ref).t()) + positionTensor(ref);
    // world -> other camera: R^T (x - c), i.e. (x - c) R for row vectors.
    const auto cam = torch::matmul(world - positionTensor(other), rotationTensor(other));
    const auto z = cam.select(-1, 2);
    const auto inFront = z > 1e-9;
    const auto safeZ = torch::where(inFront, z, torch::ones_like(z));
    auto px = cam.select(-1, 0) / safeZ * other.fx + other.cx;
    auto py = cam.select(-1, 1) / safeZ * other.fy + other.cy;
    px = torch::where(inFront, px, torch::full_like(px, -1e6));  // far outside: zeros padding
    py = torch::where(inFront, py, torch::full_like(py, -1e6));
    return torch::stack({toGridCoordinate(px, other.width), toGridCoordinate(py, other.height)}, -1)
        .to(torch::kFloat32);
}

torch::Tensor planeSweepVolume(const torch::Tensor& refImage, const torch::Tensor& srcImage,
                               const PinholeCamera& ref, const PinholeCamera& src,
                               const std::vector<double>& depths) {
    const int64_t d = int64_t(depths.size());
    const auto grid = planeWarpGrid(ref, src, depths).to(srcImage.device());
    const auto warped = F::grid_sample(srcImage.expand({d, -1, -1, -1}), grid,
                                       F::GridSampleFuncOptions()
                                           .mode(torch::kBilinear)
                                           .padding_mode(torch::kZeros)
                                           .align_corners(false));  // [D, 3, H, W]
    const auto refPlanes = refImage.expand({d, -1, -1, -1});
    return torch::cat({refPlanes, warped}, 1)
        .permute({1, 0, 2, 3})
        .unsqueeze(0);  // [1, 6, D, H, W]
}

}  // namespace lh::net
