// Ray casting against the meshes of inserted objects (Embree), with smooth shading normals
// interpolated from the vertex normals.
#pragma once

#include "insert/mesh.h"
#include "raycast/embree_scene.h"

#include <limits>
#include <vector>

namespace lh {

struct ObjectHit {
    bool hit = false;
    double t = std::numeric_limits<double>::infinity();
    int object = -1;
    Vec3d position{0.0, 0.0, 0.0};
    Vec3d normal{0.0, 0.0, 0.0};           // shading normal, unit, facing the incoming ray
    Vec3d geometricNormal{0.0, 0.0, 0.0};  // unit, facing the incoming ray
};

class ObjectTracer {
public:
    // Meshes in world coordinates; object i is meshes[i]. The meshes must outlive the tracer.
    explicit ObjectTracer(const std::vector<TriangleMesh>& meshes);

    ObjectHit intersect(const Vec3d& origin, const Vec3d& dir, double tMin = 1e-5,
                        double tMax = std::numeric_limits<double>::infinity()) const;

private:
    const std::vector<TriangleMesh>& meshes_;
    EmbreeScene scene_;
};

}  // namespace lh
