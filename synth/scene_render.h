// Ground-truth pictures of a synthetic scene: perspective views, depth maps and envmaps
// (docs/conventions.md#envmap-layout) with the first-hit positions and the observed-content mask.
#pragma once

#include "core/camera.h"
#include "image/image.h"
#include "synth/radiance_field.h"

#include <cstdint>
#include <vector>

namespace lh::synth {

// Linear radiance through every pixel; `supersample`^2 fixed sub-pixel rays per pixel. Glossy
// and metallic surfaces show their view-dependent reflection (specular_shading.h).
ImageRGB renderSceneView(const RayTracer& tracer, const RadianceField& field,
                         const PinholeCamera& camera, int supersample = 2);

// Depth along the optical axis (metres, z in the camera frame) of the first hit through each
// pixel centre, in all three channels; +inf where nothing is hit.
ImageRGB renderDepth(const RayTracer& tracer, const PinholeCamera& camera);

// Envmaps show the baked, view-independent radiance of every surface (glossy and metallic ones
// as diffuse surfaces of equal reflectance, material.h): the quantity a lighting volume
// stores, so the oracle volume reproduces them up to its resolution.
struct SceneEnvmap {
    ImageRGB radiance;              // linear, supersampled
    ImageRGB hitPositions;          // world position of the first hit along each pixel centre
    std::vector<uint8_t> observed;  // 1 where that hit is visible in the reference view
};

SceneEnvmap renderSceneEnvmap(const RayTracer& tracer, const RadianceField& field,
                              const Vec3d& position, int width, int height,
                              const PinholeCamera& reference, int supersample = 2);

// True if a world point on a surface is seen by the camera: in front of it, inside its image
// and not hidden by anything closer.
bool visibleFrom(const RayTracer& tracer, const PinholeCamera& camera, const Vec3d& point);

}  // namespace lh::synth
