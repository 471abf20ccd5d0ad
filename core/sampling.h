// Hemisphere sampling shared by the synthetic-scene baker and object insertion.
#pragma once

#include "core/vec.h"

#include <algorithm>
#include <cmath>

namespace lh {

// Two unit vectors t, b completing the unit normal n to a right-handed orthonormal frame.
inline void tangentFrame(const Vec3d& n, Vec3d& t, Vec3d& b) {
    const Vec3d helper = std::abs(n.x()) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
    t = n.cross(helper).unit();
    b = n.cross(t);
}

// Cosine-weighted direction about the unit normal n (pdf = cos / pi) from u1, u2 in [0, 1).
inline Vec3d cosineDirection(const Vec3d& n, double u1, double u2) {
    Vec3d t, b;
    tangentFrame(n, t, b);
    const double r = std::sqrt(u1), phi = 2 * M_PI * u2;
    return (t * (r * std::cos(phi)) + b * (r * std::sin(phi)) +
            n * std::sqrt(std::max(0.0, 1 - u1)))
        .unit();
}

}  // namespace lh
