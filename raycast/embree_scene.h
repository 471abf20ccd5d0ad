// A thin owner of an Embree 3 device and triangle scene: meshes in, closest hits and
// occlusion out. Both the synthetic scene tracer and the inserted-object tracer use it.
#pragma once

#include "core/vec.h"

#include <cstdint>
#include <limits>
#include <vector>

struct RTCDeviceTy;
struct RTCSceneTy;

namespace lh {

struct EmbreeHit {
    bool hit = false;
    double t = std::numeric_limits<double>::infinity();
    unsigned geometry = 0;  // the id given to addMesh
    unsigned triangle = 0;  // triangle index within that mesh
    double u = 0, v = 0;    // barycentric coordinates of the hit (vertex 1 and 2 weights)
    Vec3d geometricNormal{0.0, 0.0, 0.0};  // unnormalised, as Embree reports it
};

class EmbreeScene {
public:
    EmbreeScene();
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Adds a triangle mesh with geometry id `id`; call commit() after the last one.
    void addMesh(unsigned id, const std::vector<Vec3d>& positions,
                 const std::vector<uint32_t>& indices);
    void commit();

    // Closest hit along a unit direction within (tMin, tMax). Thread-safe after commit().
    EmbreeHit intersect(const Vec3d& origin, const Vec3d& dir, double tMin,
                        double tMax = std::numeric_limits<double>::infinity()) const;
    bool occluded(const Vec3d& origin, const Vec3d& dir, double tMin, double tMax) const;

private:
    RTCDeviceTy* device_ = nullptr;
    RTCSceneTy* scene_ = nullptr;
};

}  // namespace lh
