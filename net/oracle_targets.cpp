#include "net/oracle_targets.h"

#include "core/errors.h"
#include "vdb/volume_io.h"

#include <cmath>

namespace lh::net {

std::vector<torch::Tensor> loadOracleCubes(const std::string& path, const VolumeLayout& layout,
                                           const torch::Device& device) {
    const LightingVolume oracle = loadVolume(path);
    if (!oracle.layout)
        throw FileError(
            "'" + path +
            "' has no lighting-volume layout: not an oracle written by 'lighthouse synth'");
    const VolumeLayout& stored = *oracle.layout;
    const int factor = layout.resolution > 0 ? stored.resolution / layout.resolution : 0;
    if (stored.levels != layout.levels || std::abs(stored.s0 - layout.s0) > 1e-6 * layout.s0 ||
        factor < 1 || factor * layout.resolution != stored.resolution)
        throw FileError("'" + path + "' holds " + std::to_string(stored.levels) + " x " +
                        std::to_string(stored.resolution) + "^3 (side " +
                        std::to_string(stored.s0) + "), which does not match the network's " +
                        std::to_string(layout.levels) + " x " + std::to_string(layout.resolution) +
                        "^3 (side " + std::to_string(layout.s0) +
                        "): regenerate the data with matching --oracle-levels / --oracle-res");
    std::vector<torch::Tensor> cubes;
    const int64_t n = stored.resolution;
    for (int k = 0; k < layout.levels; ++k) {
        const double voxel = stored.voxelSize(k);
        // Dense [4, n, n, n] of (alpha * rgb, alpha), indexed [c, z, y, x].
        auto dense = torch::zeros({4, n, n, n});
        float* d = dense.data_ptr<float>();
        const auto& level = oracle.levels[size_t(k)];
        auto color = level.color->getConstAccessor();
        for (auto it = level.density->cbeginValueOn(); it; ++it) {
            const openvdb::Coord c = it.getCoord();
            if (c.x() < 0 || c.y() < 0 || c.z() < 0 || c.x() >= n || c.y() >= n || c.z() >= n)
                continue;
            const float alpha = float(-std::expm1(-double(*it) * voxel));
            const openvdb::Vec3s rgb = color.getValue(c);
            const int64_t at = (int64_t(c.z()) * n + c.y()) * n + c.x(), plane = n * n * n;
            for (int ch = 0; ch < 3; ++ch) d[ch * plane + at] = alpha * rgb[ch];
            d[3 * plane + at] = alpha;
        }
        auto cube = dense.unsqueeze(0);
        if (factor > 1)
            cube = torch::nn::functional::avg_pool3d(
                cube, torch::nn::functional::AvgPool3dFuncOptions(factor));
        const auto alpha = cube.narrow(1, 3, 1);
        const auto rgb = cube.narrow(1, 0, 3) / alpha.clamp_min(1e-6) * (alpha > 0);
        cubes.push_back(torch::cat({rgb, alpha}, 1).to(device));
    }
    return cubes;
}

}  // namespace lh::net
