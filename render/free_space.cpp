#include "render/free_space.h"

#include "core/errors.h"
#include "core/random.h"

#include <algorithm>
#include <utility>

namespace lh {

std::vector<Vec3d> freeSpacePoints(const RenderVolume& volume, int count, uint64_t seed) {
    if (volume.levels.empty()) throw InputError("volume has no levels");
    const RenderLevel& level = volume.levels[std::min<std::size_t>(1, volume.levels.size() - 1)];
    Random rng(seed);
    std::vector<Vec3d> points;
    // Candidates kept with their density: the fallback for fog needs the thinnest ones.
    std::vector<std::pair<float, Vec3d>> candidates;
    for (int tries = 0; tries < 100000 && int(points.size()) < count; ++tries) {
        Vec3d q;
        for (int a = 0; a < 3; ++a) q[a] = rng.uniform(level.domainLo[a], level.domainHi[a]);
        const Vec3d p = level.indexToWorld * (q - level.indexOffset);
        const float sigma = volume.sampleWorld(p).sigma;
        if (sigma == 0.f)
            points.push_back(p);
        else if (candidates.size() < std::size_t(64) * count)
            candidates.emplace_back(sigma, p);
    }
    if (int(points.size()) >= count) return points;
    // No (or too little) empty space: a predicted volume is dense low-alpha fog, every voxel
    // has a little density. A user queries in the air, not inside a wall, so take the
    // least dense of the first 64 x count candidates (deterministic for a seed).
    if (candidates.size() < std::size_t(count) - points.size())
        throw InputError(
            "the volume has no empty space to put query points in, nor enough sampled points");
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; int(points.size()) < count; ++i) points.push_back(candidates[i].second);
    return points;
}

}  // namespace lh
