// Ray casting against a scene's solid primitives with Embree (triangulated: boxes exactly,
// spheres as 64 x 32 and cylinders as 64-sided meshes); hits are snapped to the analytic
// surface so normals, face parameters and textures are exact.
#pragma once

#include "raycast/embree_scene.h"
#include "synth/scene.h"

#include <limits>

namespace lh::synth {

struct RayHit {
    bool hit = false;
    double t = std::numeric_limits<double>::infinity();  // metres along the unit direction
    SurfacePoint point;
};

class RayTracer {
public:
    explicit RayTracer(const Scene& scene);

    // First hit along a unit direction within (tMin, tMax). Thread-safe.
    RayHit intersect(const Vec3d& origin, const Vec3d& dir, double tMin = 1e-4,
                     double tMax = std::numeric_limits<double>::infinity()) const;
    // True if anything lies within (tMin, tMax). Thread-safe.
    bool occluded(const Vec3d& origin, const Vec3d& dir, double tMin, double tMax) const;

    std::size_t triangleCount() const { return triangles_; }

private:
    const Scene& scene_;
    EmbreeScene embree_;
    std::size_t triangles_ = 0;
};

}  // namespace lh::synth
