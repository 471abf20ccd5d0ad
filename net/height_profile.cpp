#include "net/height_profile.h"

#include "net/hdr.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace lh::net {

torch::Tensor heightProfile(const torch::Tensor& cube) {
    const auto rgb = cube.narrow(1, 0, 3), alpha = cube.narrow(1, 3, 1);
    const int64_t r = cube.size(3);
    const auto mass = alpha.sum({2, 4});                                   // [1, 1, R]
    const auto colour = (rgb * alpha).sum({2, 4}) / mass.clamp_min(1e-6);  // [1, 3, R]
    const auto coverage = 1.0 - torch::exp(-mass / double(r));
    return torch::cat({colour, coverage}, 1);
}

torch::Tensor heightProfileFeatures(const torch::Tensor& profile, const VolumeLayout& layout,
                                    int level, int networkResolution, bool hdr) {
    const int64_t slices = profile.size(2);
    const WorldBox box0 = layout.box(0), box = layout.box(level);
    const double sliceHeight = (box0.max.y() - box0.min.y()) / double(slices);  // metres
    const double voxel = (box.max.y() - box.min.y()) / double(networkResolution);
    std::vector<int64_t> index(static_cast<std::size_t>(networkResolution));
    for (int i = 0; i < networkResolution; ++i) {
        const double y = box.min.y() + (i + 0.5) * voxel;
        index[std::size_t(i)] = std::clamp<int64_t>(
            int64_t(std::floor((y - box0.min.y()) / sliceHeight)), 0, slices - 1);
    }
    const auto at =
        torch::tensor(index, torch::TensorOptions().dtype(torch::kLong)).to(profile.device());
    auto sampled = profile.index_select(2, at);  // [1, 4, r]
    if (hdr)
        sampled =
            torch::cat({radianceFeature(sampled.narrow(1, 0, 3)), sampled.narrow(1, 3, 1)}, 1);
    const int64_t r = networkResolution;
    return sampled.reshape({1, kHeightProfileChannels, 1, r, 1})
        .expand({1, kHeightProfileChannels, r, r, r});
}

}  // namespace lh::net
