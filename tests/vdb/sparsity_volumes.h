// Volumes with known answers for the sparsity tests: two levels of one linear field, and
// fog with no empty space.
#pragma once

#include "tests/support/test_volumes.h"

#include <cmath>
#include <cstdint>
#include <functional>

namespace lh::test {

// Two levels of a linear field: the finer one equals the coarser one upsampled.
inline LightingVolume twoLevelsOf(const std::function<MediumSample(const Vec3d&)>& coarse,
                                  const std::function<MediumSample(const Vec3d&)>& fine) {
    return test::volumeOf({test::makeLevel(0.1, Vec3d(-1), openvdb::Coord(20), coarse),
                           test::makeLevel(0.05, Vec3d(-0.5), openvdb::Coord(20), fine)});
}

inline MediumSample linearField(const Vec3d& p) {
    return {float(2.0 + p.x()), openvdb::Vec3s(0.5f, 0.3f, 0.2f)};
}

// Dense low-alpha fog on two nested levels, as the network predicts it: every voxel has a
// little density. Half the voxels (a hashed pattern) are very thin (sigma 1e-4), the others
// 0.05. Every voxel is "thin" for a per-voxel bound (sigma h <= 5e-3 < tau = 0.01), and
// dropping them all would darken the envmaps by far more than tau; the per-ray bound drops
// only the very thin ones and keeps every pixel within tau.
inline float fogDensity(const Vec3d& p, double h) {
    const auto i = [&](double x) { return uint32_t(int32_t(std::floor(x / h)) + 1000); };
    uint32_t k = i(p.x()) * 73856093u ^ i(p.y()) * 19349663u ^ i(p.z()) * 83492791u;
    k ^= k >> 13;
    k *= 0x5bd1e995u;
    k ^= k >> 15;
    return (k & 1) ? 0.05f : 1e-4f;
}

inline LightingVolume fogVolume() {
    return test::volumeOf(
        {test::makeLevel(
             0.1, Vec3d(-2), openvdb::Coord(40),
             [](const Vec3d& p) {
                 return MediumSample{fogDensity(p, 0.1), openvdb::Vec3s(0.9f, 0.6f, 0.3f)};
             }),
         test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), [](const Vec3d& p) {
             return MediumSample{fogDensity(p, 0.05), openvdb::Vec3s(0.3f, 0.8f, 0.5f)};
         })});
}

}  // namespace lh::test
