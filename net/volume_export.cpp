#include "net/volume_export.h"

#include "net/mpi_resample.h"

#include <algorithm>
#include <cmath>

namespace lh::net {

LightingVolume cubesToVolume(const std::vector<torch::Tensor>& cubes, const VolumeLayout& layout,
                             float minAlpha) {
    LightingVolume volume = LightingVolume::fromLayout(layout);
    for (int k = 0; k < layout.levels; ++k) {
        const auto cube =
            cubes[size_t(k)].detach().to(torch::kCPU, torch::kFloat32).squeeze(0).contiguous();
        const int64_t r = cube.size(1);
        const float* data = cube.data_ptr<float>();
        const auto at = [&](int c, int64_t z, int64_t y, int64_t x) {
            return data[((c * r + z) * r + y) * r + x];
        };
        const double voxel = layout.voxelSize(k);
        auto density = volume.levels[size_t(k)].density->getAccessor();
        auto color = volume.levels[size_t(k)].color->getAccessor();
        for (int64_t z = 0; z < r; ++z)
            for (int64_t y = 0; y < r; ++y)
                for (int64_t x = 0; x < r; ++x) {
                    const float alpha = std::min(at(3, z, y, x), float(kMaxVoxelAlpha));
                    if (!(alpha >= std::max(minAlpha, kMinStoredVoxelAlpha))) continue;
                    const openvdb::Coord ijk{int(x), int(y), int(z)};
                    density.setValue(ijk, float(-std::log1p(-double(alpha)) / voxel));
                    color.setValue(ijk,
                                   openvdb::Vec3s(at(0, z, y, x), at(1, z, y, x), at(2, z, y, x)));
                }
    }
    volume.normaliseLevels();
    return volume;
}

Mpi tensorToMpi(const torch::Tensor& mpiTensor, const PinholeCamera& camera,
                const std::vector<double>& depths) {
    Mpi mpi;
    mpi.camera = camera;
    mpi.planeDepths = depths;
    // [1, 4, D, H, W] -> [D, H, W, 4]
    const auto t = mpiTensor.detach()
                       .to(torch::kCPU, torch::kFloat32)
                       .squeeze(0)
                       .permute({1, 2, 3, 0})
                       .contiguous();
    const int64_t planeFloats = t.size(1) * t.size(2) * 4;
    for (int64_t d = 0; d < t.size(0); ++d) {
        const float* p = t.data_ptr<float>() + d * planeFloats;
        mpi.planes.emplace_back(p, p + planeFloats);
    }
    mpi.validate();
    return mpi;
}

}  // namespace lh::net
