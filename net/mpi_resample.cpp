#include "net/mpi_resample.h"

#include "net/tensor_image.h"

namespace lh::net {

namespace F = torch::nn::functional;

torch::Tensor voxelCentres(const VolumeLayout& layout, int level) {
    const WorldBox box = layout.box(level);
    const double voxel = layout.voxelSize(level);
    const auto opts = torch::TensorOptions().dtype(torch::kFloat64);
    const auto idx = torch::arange(layout.resolution, opts) + 0.5;
    const auto x = box.min.x() + idx * voxel, y = box.min.y() + idx * voxel,
               z = box.min.z() + idx * voxel;
    const auto g = torch::meshgrid({z, y, x}, "ij");
    return torch::stack({g[2], g[1], g[0]}, -1);
}

torch::Tensor densityFromAlpha(const torch::Tensor& alpha, double voxelSize) {
    return -torch::log1p(-alpha.clamp(0.0, kMaxVoxelAlpha)) / voxelSize;
}

torch::Tensor resampleMpiToLevel(const torch::Tensor& mpi, const std::vector<double>& depths,
                                 const PinholeCamera& ref, const VolumeLayout& layout, int level,
                                 double maxRadiance) {
    const int64_t planes = mpi.size(2);
    const double nearDisparity = 1.0 / depths.back(), farDisparity = 1.0 / depths.front();
    const double disparityStep =
        (nearDisparity - farDisparity) / double(std::max<int64_t>(planes - 1, 1));

    const auto cam =
        torch::matmul(voxelCentres(layout, level) - positionTensor(ref), rotationTensor(ref));
    const auto z = cam.select(-1, 2);
    const auto inFront = z > 1e-9;
    const auto safeZ = torch::where(inFront, z, torch::ones_like(z));
    const auto px = cam.select(-1, 0) / safeZ * ref.fx + ref.cx;
    const auto py = cam.select(-1, 1) / safeZ * ref.fy + ref.cy;
    const auto planeIndex = (1.0 / safeZ - farDisparity) / disparityStep;  // 0 = far plane
    const auto inside = inFront & (px >= 0) & (px <= ref.width) & (py >= 0) & (py <= ref.height) &
                        (planeIndex >= -1e-6) & (planeIndex <= double(planes - 1) + 1e-6);
    const auto grid =
        torch::stack({toGridCoordinate(px, ref.width), toGridCoordinate(py, ref.height),
                      toGridCoordinate(planeIndex + 0.5, double(planes))},
                     -1)
            .to(torch::kFloat32)
            .unsqueeze(0)
            .to(mpi.device());  // [1, R, R, R, 3]

    const auto alpha = mpi.narrow(1, 3, 1);
    const auto premultiplied = torch::cat({mpi.narrow(1, 0, 3) * alpha, alpha}, 1);
    const auto sampled = F::grid_sample(premultiplied, grid,
                                        F::GridSampleFuncOptions()
                                            .mode(torch::kBilinear)
                                            .padding_mode(torch::kBorder)
                                            .align_corners(false));  // [1, 4, R, R, R]
    const auto mask = inside.to(torch::kFloat32).to(mpi.device()).unsqueeze(0).unsqueeze(0);
    const auto mpiAlpha = sampled.narrow(1, 3, 1).clamp(0.0, kMaxVoxelAlpha);
    const auto rgb = (sampled.narrow(1, 0, 3) / mpiAlpha.clamp_min(1e-6)).clamp(0.0, maxRadiance);
    // Plane spacing (scene units) at each voxel's depth, then the voxel's own opacity.
    const auto spacing = (safeZ * safeZ * disparityStep)
                             .to(torch::kFloat32)
                             .to(mpi.device())
                             .unsqueeze(0)
                             .unsqueeze(0);
    const auto voxelAlpha =
        1.0 - torch::exp(torch::log1p(-mpiAlpha) * (layout.voxelSize(level) / spacing));
    return torch::cat({rgb, voxelAlpha}, 1) * mask;
}

}  // namespace lh::net
