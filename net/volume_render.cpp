#include "net/volume_render.h"

#include "net/mpi_resample.h"
#include "net/tensor_image.h"

#include <algorithm>
#include <cmath>

namespace lh::net {

namespace F = torch::nn::functional;

torch::Tensor envmapDirections(int width, int height) {
    const auto opts = torch::TensorOptions().dtype(torch::kFloat64);
    const auto phi = (torch::arange(height, opts) + 0.5) * (M_PI / height);
    const auto theta = (torch::arange(width, opts) + 0.5) * (2.0 * M_PI / width) - M_PI;
    const auto g = torch::meshgrid({phi, theta}, "ij");
    const auto sinPhi = torch::sin(g[0]);
    return torch::stack({sinPhi * torch::sin(g[1]), -torch::cos(g[0]), sinPhi * torch::cos(g[1])},
                        -1);
}

namespace {

double farthestCornerDistance(const WorldBox& box, const Vec3d& p) {
    double best = 0;
    for (int c = 0; c < 8; ++c) {
        const Vec3d corner((c & 1) ? box.max.x() : box.min.x(), (c & 2) ? box.max.y() : box.min.y(),
                           (c & 4) ? box.max.z() : box.min.z());
        best = std::max(best, (corner - p).length());
    }
    return best;
}

torch::Tensor insideBox(const torch::Tensor& points, const WorldBox& box) {
    const auto x = points.select(-1, 0), y = points.select(-1, 1), z = points.select(-1, 2);
    return (x >= box.min.x()) & (x <= box.max.x()) & (y >= box.min.y()) & (y <= box.max.y()) &
           (z >= box.min.z()) & (z <= box.max.z());
}

}  // namespace

torch::Tensor renderEnvmapTorch(const std::vector<torch::Tensor>& cubes, const VolumeLayout& layout,
                                const Vec3d& position, int width, int height, int samples) {
    return renderEnvmapAndTransmittanceTorch(cubes, layout, position, width, height, samples)
        .radiance;
}

TorchEnvmap renderEnvmapAndTransmittanceTorch(const std::vector<torch::Tensor>& cubes,
                                              const VolumeLayout& layout, const Vec3d& position,
                                              int width, int height, int samples) {
    const auto device = cubes.front().device();
    const int levels = int(cubes.size());
    const auto dirs = envmapDirections(width, height).view({-1, 1, 3});  // [P, 1, 3]
    const auto origin = torch::tensor({position.x(), position.y(), position.z()}, torch::kFloat64);

    std::vector<torch::Tensor> sigmas, emissions;
    std::vector<double> distances, thicknesses;
    for (int k = 0; k < levels; ++k) {
        const WorldBox box = layout.box(k);
        const double voxel = layout.voxelSize(k);
        const double dt = farthestCornerDistance(box, position) / samples;
        const auto t = (torch::arange(samples, torch::kFloat64) + 0.5) * dt;
        for (int j = 0; j < samples; ++j) {
            distances.push_back((j + 0.5) * dt);
            thicknesses.push_back(dt);
        }
        const auto points = origin + dirs * t.view({1, -1, 1});  // [P, S, 3]
        // Finest wins: this level owns the points inside it and inside no finer level.
        auto owned = insideBox(points, box);
        for (int finer = k + 1; finer < levels; ++finer)
            owned = owned & ~insideBox(points, layout.box(finer));

        const auto grid =
            ((points - torch::tensor({box.min.x(), box.min.y(), box.min.z()}, torch::kFloat64)) *
                 (2.0 / layout.side(k)) -
             1.0)
                .to(torch::kFloat32)
                .view({1, 1, -1, samples, 3})
                .to(device);
        const auto cube = cubes[size_t(k)];
        const auto sigma = densityFromAlpha(cube.narrow(1, 3, 1), voxel);
        const auto field = torch::cat({sigma, cube.narrow(1, 0, 3) * sigma}, 1);  // sigma, emission
        // Outside a finer level's faces its values continue (border), as the C++ renderer's
        // halo continues them from the coarser level; the outer level fades to empty.
        F::GridSampleFuncOptions sampling;
        sampling.mode(torch::kBilinear).align_corners(false);
        if (k == 0)
            sampling.padding_mode(torch::kZeros);
        else
            sampling.padding_mode(torch::kBorder);
        const auto sampled =
            F::grid_sample(field, grid, sampling).view({4, -1, samples});  // [4, P, S]
        const auto mask = owned.to(torch::kFloat32).to(device).unsqueeze(0);
        sigmas.push_back(sampled.narrow(0, 0, 1) * mask);
        emissions.push_back(sampled.narrow(0, 1, 3) * mask);
    }
    // Composite every level's shells in order of distance.
    std::vector<int64_t> order(distances.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = int64_t(i);
    std::stable_sort(order.begin(), order.end(),
                     [&](int64_t a, int64_t b) { return distances[a] < distances[b]; });
    std::vector<float> sortedDt(order.size());
    for (size_t i = 0; i < order.size(); ++i) sortedDt[i] = float(thicknesses[size_t(order[i])]);
    const auto index = torch::tensor(order, torch::kInt64).to(device);
    const auto dt = torch::tensor(sortedDt).to(device).view({1, 1, -1});

    const auto sigma = torch::cat(sigmas, 2).index_select(2, index);        // [1, P, N]
    const auto emission = torch::cat(emissions, 2).index_select(2, index);  // [3, P, N]
    const auto tau = sigma * dt;
    const auto opticalDepth = torch::cumsum(tau, 2);  // to the far side of each shell
    const auto transmittanceBefore = torch::exp(-(opticalDepth - tau));
    // (1 - exp(-tau)) / sigma = dt (1 - exp(-tau)) / tau, stable as tau -> 0.
    const auto smallTau = tau < 1e-4;
    const auto safeTau = torch::where(smallTau, torch::ones_like(tau), tau);
    const auto integral =
        torch::where(smallTau, dt * (1.0 - 0.5 * tau), dt * (-torch::expm1(-safeTau)) / safeTau);
    const auto radiance = (transmittanceBefore * integral * emission).sum(2);         // [3, P]
    const auto left = torch::exp(-opticalDepth.select(2, opticalDepth.size(2) - 1));  // [1, P]
    return {radiance.view({1, 3, height, width}), left.view({1, 1, height, width})};
}

std::vector<torch::Tensor> pruneCubesStraightThrough(const std::vector<torch::Tensor>& cubes,
                                                     double minAlpha) {
    if (!(minAlpha > 0)) return cubes;
    std::vector<torch::Tensor> pruned;
    pruned.reserve(cubes.size());
    for (const auto& cube : cubes) {
        const auto alpha = cube.narrow(1, 3, 1);
        const auto kept = alpha * (alpha >= minAlpha).to(alpha.dtype());
        // Forward: the pruned alpha; backward: the identity.
        const auto straightThrough = alpha + (kept - alpha).detach();
        pruned.push_back(torch::cat({cube.narrow(1, 0, 3), straightThrough}, 1));
    }
    return pruned;
}

std::vector<torch::Tensor> expandHighlightsInCubes(const std::vector<torch::Tensor>& cubes,
                                                   double gain, double knee) {
    if (gain == 1.0) return cubes;
    std::vector<torch::Tensor> expanded;
    expanded.reserve(cubes.size());
    for (const auto& cube : cubes) {
        const auto rgb = cube.narrow(1, 0, 3);
        const auto y = luminanceTensor(rgb);
        // Where Y <= knee the factor is exactly 1; the clamp keeps the unused branch finite.
        const auto above = y > knee;
        const auto safeY = y.clamp_min(knee);
        const auto factor =
            torch::where(above, (knee + gain * (safeY - knee)) / safeY, torch::ones_like(y));
        expanded.push_back(torch::cat({rgb * factor, cube.narrow(1, 3, 1)}, 1));
    }
    return expanded;
}

}  // namespace lh::net
