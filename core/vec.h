// The vector and matrix types of the whole project: OpenVDB's, in double precision (scene
// units for points, unit length for directions, linear radiance for colours).
#pragma once

#include <openvdb/math/Mat3.h>
#include <openvdb/math/Vec3.h>

namespace lh {

using Vec3d = openvdb::math::Vec3<double>;
using Mat3d = openvdb::math::Mat3<double>;

}  // namespace lh
