#include "synth/radiance_field.h"

#include "core/errors.h"
#include "core/random.h"
#include "core/sampling.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace lh::synth {

namespace {

constexpr double kSurfaceOffset = 1e-3;   // metres: ray origins leave the surface by this much
constexpr double kMinDistanceSqr = 1e-3;  // m^2: caps 1/d^2 for texels touching a lamp

// A gather ray's hit, kept so that every bounce iteration re-uses it.
struct GatherHit {
    int patch = -1;  // -1: hit an emitter or nothing (contributes only through direct light)
    float u = 0, v = 0;
    float albedoOverPi[3] = {0, 0, 0};
};

}  // namespace

RadianceField::RadianceField(const Scene& scene, const RayTracer& tracer,
                             PanoramaLibrary& panoramas, const BakeOptions& options)
    : scene_(scene) {
    for (const WindowView& w : scene.windows)
        windowPanoramas_.push_back(&panoramas.get(w.panorama));
    for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
        const Primitive& p = scene.primitives[i];
        if (p.isDecal()) decals_.push_back(int(i));
        if (p.isEmitter() && !(p.isDecal() || p.shape == Shape::Sphere))
            throw InputError("synthetic scene: only quads and spheres may emit light");
    }
    bake(tracer, options);
}

int RadianceField::decalAt(const SurfacePoint& point) const {
    if (point.primitive != scene_.roomIndex) return -1;
    for (int d : decals_) {
        const Primitive& q = scene_.primitives[d];
        const Vec3d l = q.toLocal(point.position);
        if (std::abs(l.z()) < 0.02 && std::abs(l.x()) <= q.half.x() &&
            std::abs(l.y()) <= q.half.y())
            return d;
    }
    return -1;
}

Vec3d RadianceField::decalEmission(int decal, const Vec3d& position) const {
    const Primitive& q = scene_.primitives[decal];
    if (q.emission == Emission::Constant) return q.radiance;
    if (q.emission != Emission::Window) return Vec3d(0.0);
    const WindowView& w = scene_.windows[q.window];
    // The panorama as seen from the room's centre through this point of the window.
    const Vec3d room = w.roomToWorld.transpose() * (position - w.viewCentre).unitSafe();
    const double c = std::cos(w.yaw), s = std::sin(w.yaw);
    const Vec3d turned(c * room.x() - s * room.z(), room.y(), s * room.x() + c * room.z());
    return windowPanoramas_[q.window]->radiance(turned) * w.scale;
}

Vec3d RadianceField::emitted(const SurfacePoint& point) const {
    const int decal = decalAt(point);
    if (decal >= 0) return decalEmission(decal, point.position);
    const Primitive& p = scene_.primitives[point.primitive];
    if (p.isDecal()) return decalEmission(point.primitive, point.position);
    return p.emission == Emission::Constant ? p.radiance : Vec3d(0.0);
}

bool RadianceField::isEmitting(const SurfacePoint& point) const {
    return scene_.primitives[point.primitive].isEmitter() || decalAt(point) >= 0;
}

Vec3d RadianceField::textureAlbedo(const SurfacePoint& point) const {
    const Primitive& p = scene_.primitives[point.primitive];
    return p.textureFor(point.face)
        .albedo(p.toLocal(point.position), p.rotation.transpose() * point.normal);
}

Vec3d RadianceField::albedo(const SurfacePoint& point) const {
    return viewIndependentAlbedo(scene_.primitives[point.primitive].material, textureAlbedo(point));
}

Vec3d RadianceField::interpolate(const std::vector<Vec3d>& texels, int patch, double u,
                                 double v) const {
    const Patch& P = patches_[patch];
    const double fu = (u - P.range.u0) / (P.range.u1 - P.range.u0) * P.nu - 0.5;
    const double fv =
        std::clamp((v - P.range.v0) / (P.range.v1 - P.range.v0) * P.nv - 0.5, 0.0, P.nv - 1.0);
    int u0 = int(std::floor(fu)), v0 = int(std::floor(fv));
    const double wu = P.range.periodicU ? fu - u0 : std::clamp(fu - u0, 0.0, 1.0);
    const double wv = fv - v0;
    int u1 = u0 + 1;
    const int v1 = std::min(v0 + 1, P.nv - 1);
    if (P.range.periodicU) {
        u0 = (u0 % P.nu + P.nu) % P.nu;
        u1 = (u1 % P.nu + P.nu) % P.nu;
    } else {
        u0 = std::clamp(u0, 0, P.nu - 1);
        u1 = std::clamp(u1, 0, P.nu - 1);
    }
    const auto at = [&](int iu, int iv) { return texels[P.offset + std::size_t(iv) * P.nu + iu]; };
    return (at(u0, v0) * (1 - wu) + at(u1, v0) * wu) * (1 - wv) +
           (at(u0, v1) * (1 - wu) + at(u1, v1) * wu) * wv;
}

Vec3d RadianceField::irradiance(const SurfacePoint& point) const {
    const int patch = faceStart_[point.primitive];
    if (patch < 0) return Vec3d(0.0);
    return interpolate(irradiance_, patchIndex(point.primitive, point.face), point.u, point.v);
}

Vec3d RadianceField::radiance(const SurfacePoint& point) const {
    if (isEmitting(point)) return emitted(point) * scene_.exposure;
    const Vec3d a = albedo(point), e = irradiance(point);
    return Vec3d(a.x() * e.x(), a.y() * e.y(), a.z() * e.z()) * (scene_.exposure / M_PI);
}

void RadianceField::bake(const RayTracer& tracer, const BakeOptions& options) {
    // Texel size: as asked, or larger if the surfaces would need more than maxTexels.
    double area = 0;
    for (const auto& p : scene_.primitives)
        if (!p.isDecal() && !p.isEmitter()) area += surfaceArea(p);
    texelSize_ = std::max(options.texelSize, std::sqrt(area / std::max(1, options.maxTexels)));

    faceStart_.assign(scene_.primitives.size(), -1);
    std::size_t texels = 0;
    for (std::size_t i = 0; i < scene_.primitives.size(); ++i) {
        const Primitive& p = scene_.primitives[i];
        if (p.isDecal() || p.isEmitter()) continue;
        faceStart_[i] = int(patches_.size());
        for (int f = 0; f < faceCount(p); ++f) {
            Patch patch;
            patch.range = faceRange(p, f);
            const auto count = [&](double length) {
                return std::clamp(int(std::ceil(length / texelSize_)), 1, 512);
            };
            patch.nu = count((patch.range.u1 - patch.range.u0) * patch.range.metresPerU);
            patch.nv = count((patch.range.v1 - patch.range.v0) * patch.range.metresPerV);
            patch.offset = texels;
            texels += std::size_t(patch.nu) * patch.nv;
            patches_.push_back(patch);
        }
    }
    // Texel -> (primitive, face) for the parallel loop.
    std::vector<std::pair<int, int>> texelOwner(texels);
    for (std::size_t i = 0; i < scene_.primitives.size(); ++i)
        if (faceStart_[i] >= 0)
            for (int f = 0; f < faceCount(scene_.primitives[i]); ++f) {
                const Patch& P = patches_[faceStart_[i] + f];
                std::fill_n(texelOwner.begin() + P.offset, std::size_t(P.nu) * P.nv,
                            std::make_pair(int(i), f));
            }

    const std::vector<int> emitters = scene_.emitters();
    const int strata = std::max(1, int(std::lround(std::sqrt(double(options.gatherRays)))));
    const int gather = strata * strata;
    std::vector<Vec3d> direct(texels, Vec3d(0.0));
    std::vector<GatherHit> hits(texels * gather);

    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, texels),
        [&](const tbb::blocked_range<std::size_t>& range) {
            for (std::size_t t = range.begin(); t != range.end(); ++t) {
                const auto [prim, face] = texelOwner[t];
                const Patch& P = patches_[patchIndex(prim, face)];
                const std::size_t local = t - P.offset;
                const int iu = int(local % P.nu), iv = int(local / P.nu);
                const double u = P.range.u0 + (iu + 0.5) / P.nu * (P.range.u1 - P.range.u0);
                const double v = P.range.v0 + (iv + 0.5) / P.nv * (P.range.v1 - P.range.v0);
                const SurfacePoint sp = surfaceAt(scene_.primitives[prim], prim, face, u, v);
                const Vec3d n = sp.normal, x = sp.position + n * kSurfaceOffset;
                Random rng(mixSeed(scene_.seed, t));

                // Direct light from two strategies combined by multiple importance sampling
                // (balance heuristic): K stratified samples on each emitter's area, which win for
                // small bright lamps, and the M cosine-weighted gather rays that hit an emitter,
                // which win for large ones such as a window filling half the view.
                const int k = options.lightSamples,
                          kStrata = std::max(1, int(std::sqrt(double(k))));
                // Solid-angle densities: area sampling d^2 / (cos_y A), cosine sampling cos_x / pi.
                const auto lightPdf = [](double d2, double cosY, double area) {
                    return d2 / (cosY * area);
                };
                Vec3d e(0.0);
                for (int em : emitters) {
                    const Primitive& L = scene_.primitives[em];
                    const double area = surfaceArea(L);
                    for (int s = 0; s < k; ++s) {
                        // Stratified over the emitter's parameter square (jittered grid).
                        const double a = (s % kStrata + rng.uniform()) / kStrata;
                        const double b = ((s / kStrata) % kStrata + rng.uniform()) / kStrata;
                        Vec3d y, ny, le;
                        if (L.shape == Shape::Quad) {
                            y = L.toWorld(
                                Vec3d((2 * a - 1) * L.half.x(), (2 * b - 1) * L.half.y(), 0));
                            ny = L.rotation * Vec3d(0, 0, 1);
                            le = decalEmission(em, y);
                        } else {  // sphere lamp, uniform over its area
                            const double z = 1 - 2 * a, phi = 2 * M_PI * b;
                            const double r = std::sqrt(std::max(0.0, 1 - z * z));
                            ny = Vec3d(r * std::cos(phi), r * std::sin(phi), z);
                            y = L.centre + ny * L.half.x();
                            le = L.radiance;
                        }
                        const Vec3d w = y - x;
                        const double d2 = std::max(w.lengthSqr(), kMinDistanceSqr);
                        const Vec3d wd = w / w.length();
                        const double cosX = n.dot(wd), cosY = -ny.dot(wd);
                        if (cosX <= 0 || cosY <= 0) continue;
                        if (tracer.occluded(x, wd, 1e-4, w.length() - 2 * kSurfaceOffset)) continue;
                        const double pl = lightPdf(d2, cosY, area), pc = cosX / M_PI;
                        const double weight = k * pl / (k * pl + gather * pc);
                        e += le * (weight * cosX / (pl * k));
                    }
                }

                // Gather rays: stratified cosine-weighted directions. Hits on emitters add their
                // MIS share of direct light; hits on other surfaces are kept for the bounces.
                for (int s = 0; s < gather; ++s) {
                    const double u1 = (s / strata + rng.uniform()) / strata;
                    const double u2 = (s % strata + rng.uniform()) / strata;
                    const Vec3d dir = cosineDirection(n, u1, u2);
                    const RayHit h = tracer.intersect(x, dir);
                    GatherHit& g = hits[t * gather + s];
                    if (!h.hit) continue;
                    if (isEmitting(h.point)) {
                        const int decal = decalAt(h.point);
                        const int em = decal >= 0 ? decal : h.point.primitive;
                        const Primitive& L = scene_.primitives[em];
                        const Vec3d ny = L.isDecal() ? L.rotation * Vec3d(0, 0, 1) : h.point.normal;
                        const double cosY = -ny.dot(dir), cosX = n.dot(dir);
                        const double pc = cosX / M_PI;
                        const double pl = cosY > 0 ? lightPdf(std::max(h.t * h.t, kMinDistanceSqr),
                                                              cosY, surfaceArea(L))
                                                   : 0.0;
                        const double weight = gather * pc / (k * pl + gather * pc);
                        e += emitted(h.point) * (weight * M_PI / gather);
                        continue;
                    }
                    if (faceStart_[h.point.primitive] < 0) continue;
                    g.patch = patchIndex(h.point.primitive, h.point.face);
                    g.u = float(h.point.u);
                    g.v = float(h.point.v);
                    const Vec3d a = albedo(h.point) / M_PI;
                    for (int c = 0; c < 3; ++c) g.albedoOverPi[c] = float(a[c]);
                }
                direct[t] = e;
            }
        });

    // Bounces: E_k = direct + (pi / M) sum albedo/pi * E_{k-1}(hit).
    irradiance_ = direct;
    std::vector<Vec3d> next(texels);
    for (int bounce = 0; bounce < options.bounces; ++bounce) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, texels),
                          [&](const tbb::blocked_range<std::size_t>& range) {
                              for (std::size_t t = range.begin(); t != range.end(); ++t) {
                                  Vec3d sum(0.0);
                                  for (int s = 0; s < gather; ++s) {
                                      const GatherHit& g = hits[t * gather + s];
                                      if (g.patch < 0) continue;
                                      const Vec3d e = interpolate(irradiance_, g.patch, g.u, g.v);
                                      sum += Vec3d(e.x() * g.albedoOverPi[0],
                                                   e.y() * g.albedoOverPi[1],
                                                   e.z() * g.albedoOverPi[2]);
                                  }
                                  next[t] = direct[t] + sum * (M_PI / gather);
                              }
                          });
        irradiance_.swap(next);
    }
}

}  // namespace lh::synth
