#include "raycast/embree_scene.h"

#include "core/errors.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>

namespace lh {

namespace {

RTCRay makeRay(const Vec3d& origin, const Vec3d& dir, double tMin, double tMax) {
    RTCRay ray;
    ray.org_x = float(origin.x());
    ray.org_y = float(origin.y());
    ray.org_z = float(origin.z());
    ray.dir_x = float(dir.x());
    ray.dir_y = float(dir.y());
    ray.dir_z = float(dir.z());
    ray.tnear = float(tMin);
    ray.tfar = std::isfinite(tMax) ? float(tMax) : std::numeric_limits<float>::infinity();
    ray.mask = 0xFFFFFFFF;
    ray.flags = 0;
    ray.time = 0;
    return ray;
}

}  // namespace

EmbreeScene::EmbreeScene() {
    device_ = rtcNewDevice("threads=0");
    if (!device_) throw Error("Embree could not create a device");
    scene_ = rtcNewScene(device_);
}

EmbreeScene::~EmbreeScene() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
}

void EmbreeScene::addMesh(unsigned id, const std::vector<Vec3d>& positions,
                          const std::vector<uint32_t>& indices) {
    if (indices.size() < 3) return;
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), positions.size()));
    for (std::size_t k = 0; k < positions.size(); ++k)
        for (int c = 0; c < 3; ++c) v[3 * k + c] = float(positions[k][c]);
    auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                             indices.size() / 3));
    std::copy(indices.begin(), indices.end(), t);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene_, geom, id);
    rtcReleaseGeometry(geom);
}

void EmbreeScene::commit() { rtcCommitScene(scene_); }

EmbreeHit EmbreeScene::intersect(const Vec3d& origin, const Vec3d& dir, double tMin,
                                 double tMax) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray = makeRay(origin, dir, tMin, tMax);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &rh);
    EmbreeHit hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.hit = true;
    hit.t = rh.ray.tfar;
    hit.geometry = rh.hit.geomID;
    hit.triangle = rh.hit.primID;
    hit.u = rh.hit.u;
    hit.v = rh.hit.v;
    hit.geometricNormal = Vec3d(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    return hit;
}

bool EmbreeScene::occluded(const Vec3d& origin, const Vec3d& dir, double tMin, double tMax) const {
    if (!(tMax > tMin)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = makeRay(origin, dir, tMin, tMax);
    rtcOccluded1(scene_, &context, &ray);
    return ray.tfar < 0;  // Embree sets tfar to -inf on a hit
}

}  // namespace lh
