// The multiscale layout of a lighting volume (docs/conventions.md#nested-volume-layout):
// L nested cubes of R^3 voxels. Level 0 is a cube of side s0 centred on the reference camera;
// level k >= 1 has side s0 / 2^k, spans x, y in [-s/2, s/2] and z in [0, s], so the camera sits
// on the middle of its back face and every level lies on voxel boundaries of its parent.
#pragma once

#include "core/vec.h"

#include <openvdb/math/Transform.h>

#include <string>

namespace lh {

struct WorldBox {
    Vec3d min{0.0, 0.0, 0.0};
    Vec3d max{0.0, 0.0, 0.0};
    bool contains(const Vec3d& p) const {
        return p.x() >= min.x() && p.x() <= max.x() && p.y() >= min.y() && p.y() <= max.y() &&
               p.z() >= min.z() && p.z() <= max.z();
    }
};

struct VolumeLayout {
    double s0 = 20.0;     // side of level 0, scene units
    int levels = 5;       // L, number of nested cubes
    int resolution = 64;  // R, voxels per side of every level

    // Default s0 = 2 * min(far, 20) (docs/conventions.md#nested-volume-layout).
    static VolumeLayout fromFarDepth(double far, int levels = 5, int resolution = 64);

    double side(int level) const;       // scene units
    double voxelSize(int level) const;  // scene units
    WorldBox box(int level) const;
    // Index -> world transform of a level: voxel (0,0,0) has its centre at box.min + voxel/2.
    openvdb::math::Transform::Ptr transform(int level) const;

    // Throws InputError for impossible or memory-exhausting layouts.
    void validate() const;

    std::string toJson() const;
    static VolumeLayout fromJson(const std::string& text, const std::string& sourceName);
    bool operator==(const VolumeLayout& o) const {
        return s0 == o.s0 && levels == o.levels && resolution == o.resolution;
    }
};

}  // namespace lh
