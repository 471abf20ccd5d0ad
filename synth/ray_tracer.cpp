#include "synth/ray_tracer.h"

#include "core/errors.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <vector>

namespace lh::synth {

namespace {

struct Mesh {
    std::vector<float> vertices;      // x, y, z per vertex, world frame
    std::vector<unsigned> triangles;  // 3 indices per triangle
    void vertex(const Vec3d& p) {
        vertices.insert(vertices.end(), {float(p.x()), float(p.y()), float(p.z())});
    }
    unsigned count() const { return unsigned(vertices.size() / 3); }
    void quad(unsigned a, unsigned b, unsigned c, unsigned d) {
        triangles.insert(triangles.end(), {a, b, c, a, c, d});
    }
};

constexpr int kAround = 64;  // segments around spheres and cylinders
constexpr int kPolar = 32;   // segments from pole to pole on spheres

Mesh triangulate(const Primitive& p) {
    Mesh m;
    switch (p.shape) {
        case Shape::Box:
            for (int c = 0; c < 8; ++c)
                m.vertex(p.toWorld(Vec3d((c & 1) ? p.half.x() : -p.half.x(),
                                         (c & 2) ? p.half.y() : -p.half.y(),
                                         (c & 4) ? p.half.z() : -p.half.z())));
            m.quad(0, 1, 3, 2);  // z-
            m.quad(4, 6, 7, 5);  // z+
            m.quad(0, 4, 5, 1);  // y-
            m.quad(2, 3, 7, 6);  // y+
            m.quad(0, 2, 6, 4);  // x-
            m.quad(1, 5, 7, 3);  // x+
            break;
        case Shape::Sphere:
            for (int i = 0; i <= kPolar; ++i)
                for (int j = 0; j < kAround; ++j) {
                    const double v = M_PI * i / kPolar, u = 2 * M_PI * j / kAround;
                    m.vertex(p.toWorld(Vec3d(std::sin(v) * std::cos(u), std::cos(v),
                                             std::sin(v) * std::sin(u)) * p.half.x()));
                }
            for (int i = 0; i < kPolar; ++i)
                for (int j = 0; j < kAround; ++j) {
                    const unsigned a = i * kAround + j, b = i * kAround + (j + 1) % kAround;
                    m.quad(a, b, b + kAround, a + kAround);
                }
            break;
        case Shape::Cylinder: {
            const double r = p.half.x(), h = p.half.y();
            for (int side = 0; side < 2; ++side)
                for (int j = 0; j < kAround; ++j) {
                    const double u = 2 * M_PI * j / kAround;
                    m.vertex(p.toWorld(Vec3d(r * std::cos(u), side ? h : -h, r * std::sin(u))));
                }
            m.vertex(p.toWorld(Vec3d(0, -h, 0)));
            m.vertex(p.toWorld(Vec3d(0, h, 0)));
            const unsigned bottomCentre = 2 * kAround, topCentre = bottomCentre + 1;
            for (int j = 0; j < kAround; ++j) {
                const unsigned a = j, b = (j + 1) % kAround;
                m.quad(a, b, b + kAround, a + kAround);
                m.triangles.insert(m.triangles.end(), {bottomCentre, b, a, topCentre, a + kAround, b + kAround});
            }
            break;
        }
        case Shape::Quad:
            break;  // decals are looked up on the surface they lie on, never traced
    }
    return m;
}

}  // namespace

RayTracer::RayTracer(const Scene& scene) : scene_(scene) {
    device_ = rtcNewDevice("threads=0");
    if (!device_) throw Error("Embree could not create a device");
    rtcScene_ = rtcNewScene(device_);
    for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
        const Mesh mesh = triangulate(scene.primitives[i]);
        if (mesh.triangles.empty()) continue;
        RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.count()));
        std::copy(mesh.vertices.begin(), mesh.vertices.end(), v);
        auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
            mesh.triangles.size() / 3));
        std::copy(mesh.triangles.begin(), mesh.triangles.end(), t);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(rtcScene_, geom, unsigned(i));  // geometry ID = primitive index
        rtcReleaseGeometry(geom);
        triangles_ += mesh.triangles.size() / 3;
    }
    rtcCommitScene(rtcScene_);
}

RayTracer::~RayTracer() {
    if (rtcScene_) rtcReleaseScene(rtcScene_);
    if (device_) rtcReleaseDevice(device_);
}

RayHit RayTracer::intersect(const Vec3d& origin, const Vec3d& dir, double tMin, double tMax) const {
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
    rtcIntersect1(rtcScene_, &context, &rh);
    RayHit hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.hit = true;
    hit.t = rh.ray.tfar;
    const int prim = int(rh.hit.geomID);
    hit.point = nearestSurfacePoint(scene_.primitives[prim], prim, origin + dir * hit.t);
    return hit;
}

bool RayTracer::occluded(const Vec3d& origin, const Vec3d& dir, double tMin, double tMax) const {
    if (!(tMax > tMin)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    ray.org_x = float(origin.x());
    ray.org_y = float(origin.y());
    ray.org_z = float(origin.z());
    ray.dir_x = float(dir.x());
    ray.dir_y = float(dir.y());
    ray.dir_z = float(dir.z());
    ray.tnear = float(tMin);
    ray.tfar = float(tMax);
    ray.mask = 0xFFFFFFFF;
    ray.flags = 0;
    ray.time = 0;
    rtcOccluded1(rtcScene_, &context, &ray);
    return ray.tfar < 0;  // Embree sets tfar to -inf on a hit
}

}  // namespace lh::synth
