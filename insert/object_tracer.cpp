#include "insert/object_tracer.h"

namespace lh {

ObjectTracer::ObjectTracer(const std::vector<TriangleMesh>& meshes) : meshes_(meshes) {
    for (std::size_t i = 0; i < meshes.size(); ++i)
        scene_.addMesh(unsigned(i), meshes[i].positions, meshes[i].indices);
    scene_.commit();
}

ObjectHit ObjectTracer::intersect(const Vec3d& origin, const Vec3d& dir, double tMin,
                                  double tMax) const {
    const EmbreeHit e = scene_.intersect(origin, dir, tMin, tMax);
    ObjectHit hit;
    if (!e.hit) return hit;
    hit.hit = true;
    hit.t = e.t;
    hit.object = int(e.geometry);
    hit.position = origin + dir * hit.t;
    const TriangleMesh& m = meshes_[hit.object];
    const uint32_t* tri = &m.indices[3 * std::size_t(e.triangle)];
    Vec3d shading =
        (m.normals[tri[0]] * (1 - e.u - e.v) + m.normals[tri[1]] * e.u + m.normals[tri[2]] * e.v)
            .unitSafe();
    Vec3d geometric = e.geometricNormal.unitSafe();
    if (geometric.dot(dir) > 0) geometric = -geometric;
    if (shading.dot(dir) > 0) shading = -shading;  // two-sided
    hit.normal = shading;
    hit.geometricNormal = geometric;
    return hit;
}

}  // namespace lh
