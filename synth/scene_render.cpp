#include "synth/scene_render.h"

#include "image/envmap_layout.h"
#include "synth/specular_shading.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

namespace lh::synth {

namespace {

// Radiance along one ray: the first hit's baked (view-independent) radiance, black if
// nothing is hit.
Vec3d traceRadiance(const RayTracer& tracer, const RadianceField& field, const Vec3d& origin,
                    const Vec3d& dir) {
    const RayHit hit = tracer.intersect(origin, dir, 0.0);
    return hit.hit ? field.radiance(hit.point) : Vec3d(0.0);
}

// As traceRadiance, with the view-dependent reflection of glossy and metallic surfaces.
Vec3d traceViewRadiance(const RayTracer& tracer, const RadianceField& field, const Vec3d& origin,
                        const Vec3d& dir) {
    const RayHit hit = tracer.intersect(origin, dir, 0.0);
    return hit.hit ? viewRadiance(tracer, field, hit, dir) : Vec3d(0.0);
}

template <typename PixelFn>
void forEachPixel(int width, int height, PixelFn fn) {
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < width; ++x) fn(x, y);
    });
}

void store(ImageRGB& image, int x, int y, const Vec3d& v) {
    float* p = image.at(x, y);
    for (int c = 0; c < 3; ++c) p[c] = float(v[c]);
}

}  // namespace

ImageRGB renderSceneView(const RayTracer& tracer, const RadianceField& field,
                         const PinholeCamera& camera, int supersample) {
    ImageRGB image(camera.width, camera.height);
    forEachPixel(camera.width, camera.height, [&](int x, int y) {
        Vec3d sum(0.0);
        for (int sy = 0; sy < supersample; ++sy)
            for (int sx = 0; sx < supersample; ++sx) {
                const double px = x + (sx + 0.5) / supersample, py = y + (sy + 0.5) / supersample;
                sum += traceViewRadiance(tracer, field, camera.position,
                                         camera.pixelDirection(px, py));
            }
        store(image, x, y, sum / double(supersample * supersample));
    });
    return image;
}

ImageRGB renderDepth(const RayTracer& tracer, const PinholeCamera& camera) {
    ImageRGB image(camera.width, camera.height);
    forEachPixel(camera.width, camera.height, [&](int x, int y) {
        const Vec3d dir = camera.pixelDirection(x + 0.5, y + 0.5);
        const RayHit hit = tracer.intersect(camera.position, dir, 0.0);
        const double depth = hit.hit ? camera.worldToCamera(hit.point.position).z()
                                     : std::numeric_limits<double>::infinity();
        store(image, x, y, Vec3d(depth));
    });
    return image;
}

bool visibleFrom(const RayTracer& tracer, const PinholeCamera& camera, const Vec3d& point) {
    if (!camera.projectIntoImage(point)) return false;
    const Vec3d w = point - camera.position;
    const double d = w.length();
    // Stop 5 mm short of the point: the surface it lies on must not hide it.
    return !tracer.occluded(camera.position, w / d, 1e-4, d - 5e-3);
}

SceneEnvmap renderSceneEnvmap(const RayTracer& tracer, const RadianceField& field,
                              const Vec3d& position, int width, int height,
                              const PinholeCamera& reference, int supersample) {
    SceneEnvmap env{ImageRGB(width, height), ImageRGB(width, height),
                    std::vector<uint8_t>(std::size_t(width) * height, 0)};
    forEachPixel(width, height, [&](int x, int y) {
        Vec3d sum(0.0);
        for (int sy = 0; sy < supersample; ++sy)
            for (int sx = 0; sx < supersample; ++sx) {
                const Vec3d d = envmapDirection(y + (sy + 0.5) / supersample,
                                                x + (sx + 0.5) / supersample, width, height);
                sum += traceRadiance(tracer, field, position, d);
            }
        store(env.radiance, x, y, sum / double(supersample * supersample));
        const RayHit hit =
            tracer.intersect(position, envmapPixelDirection(y, x, width, height), 0.0);
        if (hit.hit) {
            store(env.hitPositions, x, y, hit.point.position);
            env.observed[std::size_t(y) * width + x] =
                visibleFrom(tracer, reference, hit.point.position);
        }
    });
    return env;
}

}  // namespace lh::synth
