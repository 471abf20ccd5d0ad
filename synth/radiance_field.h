// Light transport in a synthetic scene, baked once: the radiance leaving every surface point.
//
// Every surface is treated as diffuse, so outgoing radiance is emission + albedo / pi *
// irradiance and does not depend on the view direction; glossy and metallic surfaces take
// the albedo of equal total reflectance (material.h). Irradiance is stored on texels (about 10 cm)
// over every non-emitting face and interpolated bilinearly; albedo is evaluated at full resolution
// where a surface is seen. Per texel:
//   direct   = stratified samples on every emitter with shadow rays, and gather rays that hit
//              emitters, combined by multiple importance sampling (balance heuristic);
//   indirect = the cosine-weighted gather rays, traced once; their hits on other surfaces are
//              re-used by `bounces` iterations E_k = direct + pi/M sum albedo(hit)/pi E_{k-1}(hit).
// Deterministic: each texel has its own random stream seeded from the scene seed.
#pragma once

#include "synth/panorama.h"
#include "synth/ray_tracer.h"
#include "synth/scene.h"

#include <vector>

namespace lh::synth {

struct BakeOptions {
    double texelSize = 0.1;  // metres; grown if the scene would need more than maxTexels
    int maxTexels = 20000;
    int gatherRays = 64;    // per texel (a square number stratifies best)
    int lightSamples = 16;  // per texel and emitter
    int bounces = 4;        // diffuse interreflections after the direct light
};

class RadianceField {
public:
    // `panoramas` must already hold every panorama the scene's windows use.
    RadianceField(const Scene& scene, const RayTracer& tracer, PanoramaLibrary& panoramas,
                  const BakeOptions& options = {});

    // Outgoing radiance (linear, times the scene's exposure) at a surface point.
    Vec3d radiance(const SurfacePoint& point) const;
    // Emitted radiance (before exposure); zero for non-emitters. Windows and panels lying on
    // the room's walls are found here.
    Vec3d emitted(const SurfacePoint& point) const;
    bool isEmitting(const SurfacePoint& point) const;
    Vec3d irradiance(const SurfacePoint& point) const;  // before exposure
    // The view-independent albedo light transport uses (material.h): the texture's albedo,
    // raised by the specular reflectance on glossy and metallic surfaces.
    Vec3d albedo(const SurfacePoint& point) const;
    // The texture's albedo alone: the diffuse lobe of a glossy or metallic surface.
    Vec3d textureAlbedo(const SurfacePoint& point) const;

    const Scene& scene() const { return scene_; }

    std::size_t texelCount() const { return irradiance_.size(); }
    double texelSize() const { return texelSize_; }

private:
    struct Patch {
        int nu = 0, nv = 0;
        std::size_t offset = 0;  // first texel
        FaceRange range{};
    };
    int patchIndex(int primitive, int face) const { return faceStart_[primitive] + face; }
    // Decal (window or panel) covering a room point, or -1.
    int decalAt(const SurfacePoint& point) const;
    Vec3d decalEmission(int decal, const Vec3d& position) const;
    Vec3d interpolate(const std::vector<Vec3d>& texels, int patch, double u, double v) const;
    void bake(const RayTracer& tracer, const BakeOptions& options);

    const Scene& scene_;
    std::vector<const Panorama*> windowPanoramas_;  // per WindowView
    std::vector<int> decals_;
    std::vector<int> faceStart_;  // per primitive: index of its first patch (-1: none)
    std::vector<Patch> patches_;
    std::vector<Vec3d> irradiance_;  // per texel
    double texelSize_ = 0.1;
};

}  // namespace lh::synth
