#include "synth/specular_shading.h"

#include "core/random.h"
#include "core/sampling.h"

#include <cmath>
#include <cstring>

namespace lh::synth {

namespace {

constexpr double kSurfaceOffset = 1e-3;  // metres: reflected rays leave the surface by this much

uint64_t bitsOf(double x) {
    uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

// A random stream fixed by the ray, so that the jitter does not depend on evaluation order.
Random rayStream(const Vec3d& position, const Vec3d& dir) {
    uint64_t seed = 0x5EED5EEDull;
    for (int c = 0; c < 3; ++c) seed = mixSeed(seed, bitsOf(position[c]) ^ (bitsOf(dir[c]) * 31));
    return Random(seed);
}

}  // namespace

Vec3d viewRadiance(const RayTracer& tracer, const RadianceField& field, const RayHit& hit,
                   const Vec3d& dir) {
    const SurfacePoint& point = hit.point;
    const Primitive& prim = field.scene().primitives[point.primitive];
    if (!prim.material.isSpecular() || field.isEmitting(point)) return field.radiance(point);

    const Vec3d n = point.normal;
    const double cosView = -dir.dot(n);
    if (cosView <= 0) return field.radiance(point);  // seen from behind (grazing mesh hits)
    const Vec3d mirror = (dir + n * (2 * cosView)).unit();
    const Vec3d origin = point.position + n * kSurfaceOffset;

    // Reflected radiance: the mirror direction, or the mean over a uniformly sampled cone of
    // half-angle `roughness` about it (stratified, jittered); directions below the surface are
    // folded back above it.
    Vec3d reflected(0.0);
    const double roughness = prim.material.roughness;
    const int rays = roughness > 0 ? kGlossyRays : 1;
    const int strata = int(std::lround(std::sqrt(double(rays))));
    Random rng = rayStream(point.position, dir);
    Vec3d t, b;
    tangentFrame(mirror, t, b);
    for (int s = 0; s < rays; ++s) {
        Vec3d w = mirror;
        if (roughness > 0) {
            const double u1 = (s / strata + rng.uniform()) / strata,
                         u2 = (s % strata + rng.uniform()) / strata;
            const double cosTheta = 1 - u1 * (1 - std::cos(roughness)), phi = 2 * M_PI * u2;
            const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
            w = (t * (sinTheta * std::cos(phi)) + b * (sinTheta * std::sin(phi)) +
                 mirror * cosTheta)
                    .unit();
            if (w.dot(n) <= 0) w = (w - n * (2 * w.dot(n))).unit();
        }
        const RayHit r = tracer.intersect(origin, w, 0.0);
        if (r.hit) reflected += field.radiance(r.point);
    }
    reflected /= double(rays);

    const Vec3d fresnel = fresnelSchlick(prim.material.f0, cosView);
    const Vec3d albedo = field.textureAlbedo(point), e = field.irradiance(point);
    const double diffuseScale = field.scene().exposure / M_PI;
    Vec3d out;
    for (int c = 0; c < 3; ++c)
        out[c] = (1 - fresnel[c]) * albedo[c] * e[c] * diffuseScale + fresnel[c] * reflected[c];
    return out;
}

}  // namespace lh::synth
