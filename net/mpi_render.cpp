#include "net/mpi_render.h"

#include "net/tensor_image.h"

namespace lh::net {

namespace F = torch::nn::functional;

namespace {

// For each target pixel and plane, where the target ray meets the plane z = depth of the
// reference camera, as reference grid_sample coordinates [D, Ht, Wt, 2].
torch::Tensor targetToPlaneGrid(const PinholeCamera& ref, const PinholeCamera& target,
                                const std::vector<double>& depths) {
    const auto rays = torch::matmul(pixelRaysCamera(target), rotationTensor(target).t());  // world
    // Into the reference camera frame.
    const auto origin =
        torch::matmul(positionTensor(target) - positionTensor(ref), rotationTensor(ref));
    const auto dir = torch::matmul(rays, rotationTensor(ref));  // [Ht, Wt, 3]
    const auto depth = torch::tensor(depths, torch::kFloat64).view({-1, 1, 1});
    const auto dz = dir.select(-1, 2).unsqueeze(0);
    const auto valid = dz.abs() > 1e-12;
    const auto s =
        (depth - origin[2]) / torch::where(valid, dz, torch::ones_like(dz));  // [D, Ht, Wt]
    const auto hits = valid & (s > 0);
    const auto x = origin[0] + s * dir.select(-1, 0).unsqueeze(0);
    const auto y = origin[1] + s * dir.select(-1, 1).unsqueeze(0);
    auto px = x / depth * ref.fx + ref.cx;
    auto py = y / depth * ref.fy + ref.cy;
    px = torch::where(hits, px, torch::full_like(px, -1e6));
    py = torch::where(hits, py, torch::full_like(py, -1e6));
    return torch::stack({toGridCoordinate(px, ref.width), toGridCoordinate(py, ref.height)}, -1)
        .to(torch::kFloat32);
}

}  // namespace

torch::Tensor compositePlanes(const torch::Tensor& planes) {
    const auto alpha = planes.narrow(1, 3, 1);  // [D, 1, H, W]
    // Transmittance in front of plane d: product of (1 - alpha) over nearer planes d' > d.
    const auto logClear = torch::log1p(-alpha.clamp(0.0, 1.0 - 1e-6));
    const auto nearerSum = logClear.flip(0).cumsum(0).flip(0) - logClear;
    const auto weights = torch::exp(nearerSum);
    return (planes.narrow(1, 0, 3) * weights).sum(0, /*keepdim=*/true);
}

torch::Tensor renderMpiView(const torch::Tensor& mpi, const std::vector<double>& depths,
                            const PinholeCamera& ref, const PinholeCamera& target) {
    const auto planes = mpi.squeeze(0).permute({1, 0, 2, 3});  // [D, 4, H, W]
    const auto alpha = planes.narrow(1, 3, 1);
    const auto premultiplied = torch::cat({planes.narrow(1, 0, 3) * alpha, alpha}, 1);
    const auto grid = targetToPlaneGrid(ref, target, depths).to(mpi.device());
    const auto warped = F::grid_sample(premultiplied, grid,
                                       F::GridSampleFuncOptions()
                                           .mode(torch::kBilinear)
                                           .padding_mode(torch::kZeros)
                                           .align_corners(false));
    return compositePlanes(warped);
}

}  // namespace lh::net
