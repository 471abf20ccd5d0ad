// Volumes with known answers for the tests: single levels over a box, filled from a field.
#pragma once

#include "vdb/lighting_volume.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace lh::test {

// One level of cubic voxels of side `voxel` whose domain covers [lo, lo + dims * voxel)
// (voxel faces), filled from `field` at voxel centres.
inline VolumeLevel makeLevel(double voxel, const Vec3d& lo, const openvdb::Coord& dims,
                             const std::function<MediumSample(const Vec3d&)>& field) {
    LightingVolume v;
    VolumeLevel level;
    level.density = openvdb::FloatGrid::create(0.f);
    level.color = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    auto xf = openvdb::math::Transform::createLinearTransform(voxel);
    xf->postTranslate(lo + Vec3d(voxel / 2));
    level.density->setTransform(xf);
    level.color->setTransform(xf->copy());
    level.domain = openvdb::CoordBBox(openvdb::Coord(0), dims - openvdb::Coord(1));
    v.levels.push_back(level);
    v.fillLevel(0, field);
    return v.levels[0];
}

inline LightingVolume volumeOf(std::vector<VolumeLevel> levels) {
    LightingVolume v;
    v.levels = std::move(levels);
    v.normaliseLevels();
    return v;
}

// A field that is `inside` within the box [lo, hi] and empty elsewhere.
inline std::function<MediumSample(const Vec3d&)> boxField(const Vec3d& lo, const Vec3d& hi,
                                                          MediumSample inside) {
    return [=](const Vec3d& p) {
        const bool in = p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y() &&
                        p.z() >= lo.z() && p.z() <= hi.z();
        return in ? inside : MediumSample{};
    };
}

// A homogeneous medium (sigma 1.5, radiance (2, 1, 0.5)) between |p|_inf = 1 and 2, a box
// shell around the origin, on one level of 0.05 voxels.
inline LightingVolume boxShellVolume() {
    return volumeOf({makeLevel(0.05, Vec3d(-2), openvdb::Coord(80), [](const Vec3d& p) {
        const double m = std::max({std::abs(p.x()), std::abs(p.y()), std::abs(p.z())});
        return m > 1.0 ? MediumSample{1.5f, openvdb::Vec3s(2.f, 1.f, 0.5f)} : MediumSample{};
    })});
}

}  // namespace lh::test
