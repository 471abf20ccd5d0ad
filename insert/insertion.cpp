#include "insert/insertion.h"

#include "core/errors.h"
#include "core/random.h"
#include "core/sampling.h"
#include "image/envmap_lookup.h"
#include "insert/object_tracer.h"
#include "render/envmap.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>

namespace lh {

namespace {

Vec3d times(const Vec3d& a, const Vec3d& b) {
    return Vec3d(a.x() * b.x(), a.y() * b.y(), a.z() * b.z());
}

class Inserter {
public:
    Inserter(const RenderVolume& volume, const std::vector<InsertedObject>& objects,
             const InsertOptions& o)
        : volume_(volume),
          objects_(objects),
          options_(o),
          meshes_(meshesOf(objects)),
          tracer_(meshes_) {
        if (o.singleEnvmap)
            for (const auto& obj : objects)
                envmaps_.push_back(renderEnvmap(volume, obj.centre,
                                                {2 * o.envmapHeight, o.envmapHeight, o.march}));
    }

    const ObjectTracer& tracer() const { return tracer_; }

    // Light arriving at `origin` from direction `dir`, as seen by object `from`.
    Vec3d environment(const Vec3d& origin, const Vec3d& dir, int from) const {
        if (options_.singleEnvmap) return sampleEnvmap(envmaps_[from], dir);
        const RayResult r = marchRay(volume_, origin, dir, options_.march);
        return Vec3d(r.radiance[0], r.radiance[1], r.radiance[2]);
    }

    // Radiance along a ray leaving object `from` (or the camera, from = -1).
    Vec3d trace(const Vec3d& origin, const Vec3d& dir, int depth, int from, Random& rng) const {
        const ObjectHit hit = tracer_.intersect(origin, dir);
        if (hit.hit && depth < options_.maxDepth) return shade(hit, dir, depth + 1, rng);
        return environment(origin, dir, std::max(from, 0));
    }

    // Radiance leaving an object's surface point towards the ray's origin.
    Vec3d shade(const ObjectHit& hit, const Vec3d& dir, int depth, Random& rng) const {
        const Material& m = objects_[hit.object].material;
        const Vec3d p =
            hit.position + hit.geometricNormal * (1e-4 * (1 + objects_[hit.object].radius));
        // `samples` rays per pixel at the first surface, shared by the pixel's primary rays;
        // one ray per bounce after it (path tracing).
        const int perPrimary =
            std::max(1, options_.samples / (options_.pixelSamples * options_.pixelSamples));
        const int count = m.kind == Material::Kind::Mirror ? 1 : (depth == 1 ? perPrimary : 1);
        const int strata = std::max(1, int(std::sqrt(double(count))));
        Vec3d sum(0.0);
        int below = 0;
        for (int s = 0; s < count; ++s) {
            double u1 = rng.uniform(), u2 = rng.uniform();
            if (s < strata * strata)
                u1 = (s / strata + u1) / strata, u2 = (s % strata + u2) / strata;
            const MaterialSample ms = sampleMaterial(m, hit.normal, dir, u1, u2);
            // Smooth normals on a tessellated surface send a few samples under the triangle
            // itself; they are dropped and the rest renormalised, so no energy is lost.
            if (ms.direction.dot(hit.geometricNormal) <= 0) {
                ++below;
                continue;
            }
            if (ms.weight.x() <= 0 && ms.weight.y() <= 0 && ms.weight.z() <= 0) continue;
            sum += times(ms.weight, trace(p, ms.direction, depth, hit.object, rng));
        }
        return below < count ? sum / double(count - below) : Vec3d(0.0);
    }

    // The volume's light arriving at the scene surface at the end of a camera ray, as
    // irradiance / pi (the radiance a white diffuse surface would reflect): all of it, and the
    // part the objects block. Zero where no object is near.
    struct SurfaceLight {
        Vec3d incident{0.0, 0.0, 0.0};
        Vec3d blocked{0.0, 0.0, 0.0};
    };
    SurfaceLight surfaceLight(const Vec3d& eye, const Vec3d& dir, double surface,
                              Random& rng) const {
        if (!std::isfinite(surface)) return {};
        const Vec3d x = eye + dir * surface;
        // Receivers: surfaces beneath an object (below its centre, +y is down) within 3 radii.
        bool near = false;
        for (const auto& obj : objects_)
            near |= (x - obj.centre).length() < 3 * obj.radius && x.y() > obj.centre.y();
        if (!near) return {};
        // Surface normal: minus the density gradient (1 cm central differences).
        const double h = 0.01;
        Vec3d g;
        for (int a = 0; a < 3; ++a) {
            Vec3d e(0.0);
            e[a] = h;
            g[a] = (volume_.sampleWorld(x + e).sigma - volume_.sampleWorld(x - e).sigma) / (2 * h);
        }
        Vec3d n = g.lengthSqr() > 1e-12 ? -g.unit() : -dir;
        if (n.dot(dir) > 0) n = -n;
        // Only upward-facing supports (floors, tables; normal within 45 degrees of up, -y)
        // receive shadows: walls and emitters keep the photo's light.
        if (n.y() > -0.7) return {};
        // Start in front of the surface's trilinear ramp (about a voxel deep), so that the
        // rays do not pick up the surface's own emission on their way out.
        const double voxel = std::max(0.01, volume_.voxelSizeAt(x));
        const Vec3d y = x - dir * (1.5 * voxel) + n * (0.5 * voxel);
        const int k = options_.shadowRays, strata = std::max(1, int(std::sqrt(double(k))));
        SurfaceLight result;
        for (int s = 0; s < k; ++s) {
            double u1 = rng.uniform(), u2 = rng.uniform();
            if (s < strata * strata)
                u1 = (s / strata + u1) / strata, u2 = (s % strata + u2) / strata;
            const Vec3d d = cosineDirection(n, u1, u2);
            const RayResult light = marchRay(volume_, y, d, options_.march);
            const Vec3d l(light.radiance[0], light.radiance[1], light.radiance[2]);
            result.incident += l / double(k);  // cosine-weighted: E / pi = mean radiance
            const ObjectHit hit = tracer_.intersect(y, d);
            if (hit.hit && hit.t < light.surfaceDistance) result.blocked += l / double(k);
        }
        return result;
    }

private:
    static std::vector<TriangleMesh> meshesOf(const std::vector<InsertedObject>& objects) {
        std::vector<TriangleMesh> meshes;
        for (const auto& o : objects) meshes.push_back(o.mesh);
        return meshes;
    }

    const RenderVolume& volume_;
    const std::vector<InsertedObject>& objects_;
    const InsertOptions& options_;
    std::vector<TriangleMesh> meshes_;
    ObjectTracer tracer_;
    std::vector<ImageRGB> envmaps_;  // single-envmap mode: one per object
};

}  // namespace

InsertedObject placeObject(TriangleMesh mesh, const Material& material, const Vec3d& at,
                           double radius, const Mat3d& rotation) {
    if (!(radius > 0) || !std::isfinite(radius)) throw InputError("object scale must be positive");
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(at[a])) throw InputError("object position must be finite");
    mesh.transform(radius, rotation, at);
    return {std::move(mesh), material, at, radius};
}

void InsertOptions::validate() const {
    if (samples < 1 || samples > 65536) throw InputError("--samples must be in [1, 65536]");
    if (pixelSamples < 1 || pixelSamples > 16)
        throw InputError("--pixel-samples must be in [1, 16]");
    if (maxDepth < 1 || maxDepth > 16) throw InputError("--max-depth must be in [1, 16]");
    if (envmapHeight < 1 || envmapHeight > 4096)
        throw InputError("envmap height must be in [1, 4096]");
    if (shadowRays < 1 || shadowRays > 4096) throw InputError("--shadow-rays must be in [1, 4096]");
    march.validate();
}

ImageRGB insertObjects(const RenderVolume& volume, const ImageRGB& background,
                       const PinholeCamera& camera, const std::vector<InsertedObject>& objects,
                       const InsertOptions& options, std::vector<ObjectVisibility>* visibility) {
    options.validate();
    camera.validate("insertion camera");
    if (background.width != camera.width || background.height != camera.height)
        throw InputError("image is " + std::to_string(background.width) + "x" +
                         std::to_string(background.height) + " but the camera is " +
                         std::to_string(camera.width) + "x" + std::to_string(camera.height));
    if (objects.empty()) throw InputError("nothing to insert: give at least one object");
    const Inserter inserter(volume, objects, options);
    ImageRGB out(camera.width, camera.height);
    std::vector<std::atomic<long>> raysHit(objects.size()), raysVisible(objects.size());
    const int n = options.pixelSamples;

    // Shadows are smooth: the surface light is computed on every other pixel and row (at the
    // pixel centres of a half-resolution grid) and interpolated bilinearly, a quarter of the
    // rays. Every grid point uses the same stratified directions, so the estimate varies
    // smoothly across the image instead of speckling.
    const int sw = (camera.width + 1) / 2 + 1, sh = (camera.height + 1) / 2 + 1;
    std::vector<Inserter::SurfaceLight> shadowGrid(std::size_t(sw) * sh);
    if (options.shadows)
        tbb::parallel_for(tbb::blocked_range<int>(0, sh), [&](const tbb::blocked_range<int>& rows) {
            for (int gy = rows.begin(); gy != rows.end(); ++gy)
                for (int gx = 0; gx < sw; ++gx) {
                    const Vec3d d = camera.pixelDirection(2 * gx + 0.5, 2 * gy + 0.5);
                    // Only rays passing within 3 radii of an object can end in its shadow.
                    bool near = false;
                    for (const auto& o : objects) {
                        const Vec3d v = o.centre - camera.position;
                        near |= (v - d * std::max(0.0, v.dot(d))).length() < 3 * o.radius;
                    }
                    if (!near) continue;
                    Random rng(0x5AD0u);
                    const double surface =
                        marchRay(volume, camera.position, d, options.march).surfaceDistance;
                    shadowGrid[std::size_t(gy) * sw + gx] =
                        inserter.surfaceLight(camera.position, d, surface, rng);
                }
        });
    // Differential rendering: the photo loses albedo * blocked light, with the albedo
    // estimated as a = photo / incident light. A surface brighter than a white reflector
    // (a > 1) emits: windows and lamps are not shadowed (the weight fades from 1 at a = 1 to
    // 0 at a = 2, so that noise near a = 1 leaves no seam).
    const auto shadowed = [&](int x, int y, const Vec3d& photo) {
        const double fx = x / 2.0, fy = y / 2.0;
        const int x0 = int(fx), y0 = int(fy);
        const double wx = fx - x0, wy = fy - y0;
        Vec3d incident(0.0), blocked(0.0);
        for (int c = 0; c < 4; ++c) {
            const int gx = std::min(x0 + (c & 1), sw - 1), gy = std::min(y0 + (c >> 1), sh - 1);
            const double w = ((c & 1) ? wx : 1 - wx) * ((c >> 1) ? wy : 1 - wy);
            incident += shadowGrid[std::size_t(gy) * sw + gx].incident * w;
            blocked += shadowGrid[std::size_t(gy) * sw + gx].blocked * w;
        }
        Vec3d out = photo;
        for (int c = 0; c < 3; ++c)
            if (incident[c] > 0) {
                const double a = photo[c] / incident[c];
                out[c] -= (a <= 1 ? a : std::max(0.0, 2 - a)) * blocked[c];
            }
        return out;
    };
    tbb::parallel_for(
        tbb::blocked_range<int>(0, camera.height), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y != rows.end(); ++y)
                for (int x = 0; x < camera.width; ++x) {
                    Random rng(mixSeed(0x1A5E27u, uint64_t(y) * camera.width + x));
                    const float* bg = background.at(x, y);
                    const Vec3d photo(bg[0], bg[1], bg[2]);
                    // The real scene's depth along the pixel centre, computed lazily: only pixels
                    // whose rays meet an object need it.
                    double surface = -1;
                    const auto sceneSurface = [&] {
                        if (surface < 0)
                            surface =
                                marchRay(volume, camera.position,
                                         camera.pixelDirection(x + 0.5, y + 0.5), options.march)
                                    .surfaceDistance;
                        return surface;
                    };
                    Vec3d sum(0.0);
                    for (int s = 0; s < n * n; ++s) {
                        const Vec3d d =
                            camera.pixelDirection(x + (s % n + 0.5) / n, y + (s / n + 0.5) / n);
                        const ObjectHit hit = inserter.tracer().intersect(camera.position, d, 0.0);
                        if (hit.hit)
                            raysHit[std::size_t(hit.object)].fetch_add(1,
                                                                       std::memory_order_relaxed);
                        if (hit.hit && hit.t < sceneSurface()) {
                            raysVisible[std::size_t(hit.object)].fetch_add(
                                1, std::memory_order_relaxed);
                            sum += inserter.shade(hit, d, 1, rng);
                            continue;
                        }
                        sum += shadowed(x, y, photo);
                    }
                    sum /= double(n * n);
                    float* px = out.at(x, y);
                    for (int c = 0; c < 3; ++c) px[c] = float(sum[c]);
                }
        });
    if (visibility) {
        visibility->assign(objects.size(), {});
        for (std::size_t i = 0; i < objects.size(); ++i)
            (*visibility)[i] = {raysHit[i].load(), raysVisible[i].load()};
    }
    return out;
}

std::string hiddenReason(const InsertedObject& object, const PinholeCamera& camera,
                         const ObjectVisibility& visibility) {
    if (visibility.raysVisible > 0) return "";
    const Vec3d centre = camera.worldToCamera(object.centre);  // camera frame, +z forward
    std::ostringstream why;
    why.precision(3);
    if (visibility.raysHit > 0) {
        why << "it is behind the scene's surface: along all " << visibility.raysHit
            << " of its camera rays the photo's scene is nearer (the volume's transmittance falls "
               "below 1/2 first)";
        return why.str();
    }
    bool inFront = false;
    for (const Vec3d& v : object.mesh.positions) inFront |= camera.worldToCamera(v).z() > 0;
    if (!inFront) {
        why << "it is behind the camera (its centre is at depth " << centre.z()
            << " along the camera's +z axis)";
        return why.str();
    }
    if (centre.z() > 0) {
        const Vec3d pixel = camera.cameraToPixel(centre);
        const double margin = object.radius * camera.fx / centre.z();  // its radius, pixels
        if (pixel.x() + margin < 0 || pixel.x() - margin > camera.width || pixel.y() + margin < 0 ||
            pixel.y() - margin > camera.height) {
            why << "it is outside the image (its centre projects to pixel (" << pixel.x() << ", "
                << pixel.y() << "); the image is " << camera.width << "x" << camera.height << ")";
            return why.str();
        }
    }
    return "it is hidden behind another inserted object, or too small to cover a pixel";
}

}  // namespace lh
