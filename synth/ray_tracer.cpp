#include "synth/ray_tracer.h"

#include <cmath>
#include <vector>

namespace lh::synth {

namespace {

struct Mesh {
    std::vector<Vec3d> vertices;      // world frame
    std::vector<uint32_t> triangles;  // 3 indices per triangle
    void vertex(const Vec3d& p) { vertices.push_back(p); }
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
                    m.vertex(p.toWorld(
                        Vec3d(std::sin(v) * std::cos(u), std::cos(v), std::sin(v) * std::sin(u)) *
                        p.half.x()));
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
                m.triangles.insert(m.triangles.end(),
                                   {bottomCentre, b, a, topCentre, a + kAround, b + kAround});
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
    for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
        const Mesh mesh = triangulate(scene.primitives[i]);
        embree_.addMesh(unsigned(i), mesh.vertices, mesh.triangles);  // geometry id = primitive
        triangles_ += mesh.triangles.size() / 3;
    }
    embree_.commit();
}

RayHit RayTracer::intersect(const Vec3d& origin, const Vec3d& dir, double tMin, double tMax) const {
    const EmbreeHit e = embree_.intersect(origin, dir, tMin, tMax);
    RayHit hit;
    if (!e.hit) return hit;
    hit.hit = true;
    hit.t = e.t;
    const int prim = int(e.geometry);
    hit.point = nearestSurfacePoint(scene_.primitives[prim], prim, origin + dir * hit.t);
    return hit;
}

bool RayTracer::occluded(const Vec3d& origin, const Vec3d& dir, double tMin, double tMax) const {
    return embree_.occluded(origin, dir, tMin, tMax);
}

}  // namespace lh::synth
