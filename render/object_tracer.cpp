#include "render/object_tracer.h"

#include "core/errors.h"

#include <embree3/rtcore.h>

#include <cmath>

namespace lh {

ObjectTracer::ObjectTracer(const std::vector<TriangleMesh>& meshes) : meshes_(meshes) {
    device_ = rtcNewDevice("threads=0");
    if (!device_) throw Error("Embree could not create a device");
    scene_ = rtcNewScene(device_);
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const TriangleMesh& m = meshes[i];
        RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                              RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                              m.positions.size()));
        for (std::size_t k = 0; k < m.positions.size(); ++k)
            for (int c = 0; c < 3; ++c) v[3 * k + c] = float(m.positions[k][c]);
        auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                                 RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                                 m.triangleCount()));
        std::copy(m.indices.begin(), m.indices.end(), t);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(scene_, geom, unsigned(i));
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(scene_);
}

ObjectTracer::~ObjectTracer() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
}

ObjectHit ObjectTracer::intersect(const Vec3d& origin, const Vec3d& dir, double tMin, double tMax) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray.org_x = float(origin.x());
    rh.ray.org_y = float(origin.y());
    rh.ray.org_z = float(origin.z());
    rh.ray.dir_x = float(dir.x());
    rh.ray.dir_y = float(dir.y());
    rh.ray.dir_z = float(dir.z());
    rh.ray.tnear = float(tMin);
    rh.ray.tfar = std::isfinite(tMax) ? float(tMax) : std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xFFFFFFFF;
    rh.ray.flags = 0;
    rh.ray.time = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &rh);
    ObjectHit hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.hit = true;
    hit.t = rh.ray.tfar;
    hit.object = int(rh.hit.geomID);
    hit.position = origin + dir * hit.t;
    const TriangleMesh& m = meshes_[hit.object];
    const uint32_t* tri = &m.indices[3 * std::size_t(rh.hit.primID)];
    const double u = rh.hit.u, v = rh.hit.v;
    Vec3d shading = m.normals[tri[0]] * (1 - u - v) + m.normals[tri[1]] * u + m.normals[tri[2]] * v;
    Vec3d geometric = Vec3d(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z).unitSafe();
    if (geometric.dot(dir) > 0) geometric = -geometric;
    shading = shading.unitSafe();
    if (shading.dot(dir) > 0) shading = -shading;  // two-sided
    hit.normal = shading;
    hit.geometricNormal = geometric;
    return hit;
}

}  // namespace lh
