// Volumes for the edit tests: two nested levels, coarse [-4, 4]^3 and fine [-1, 1]^3.
#pragma once

#include "tests/support/test_volumes.h"

namespace lh::test {

// An empty two-level volume: coarse [-4, 4]^3 (0.2 voxels), fine [-1, 1]^3 (0.05 voxels).
inline LightingVolume emptyVolume() {
    const auto nothing = [](const Vec3d&) { return MediumSample{}; };
    return test::volumeOf({test::makeLevel(0.2, Vec3d(-4), openvdb::Coord(40), nothing),
                           test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), nothing)});
}

inline LightingVolume uniformVolume(float sigma, openvdb::Vec3s color) {
    const auto field = [=](const Vec3d&) { return MediumSample{sigma, color}; };
    return test::volumeOf({test::makeLevel(0.2, Vec3d(-4), openvdb::Coord(40), field),
                           test::makeLevel(0.05, Vec3d(-1), openvdb::Coord(40), field)});
}

}  // namespace lh::test
