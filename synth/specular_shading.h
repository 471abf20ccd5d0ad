// What a camera sees on glossy and metallic surfaces: the baked diffuse light weighted by
// 1 - F plus the Fresnel-weighted reflection F * L_r (material.h), L_r traced with the ray
// tracer into the baked, view-independent radiance field (one specular bounce: a mirror seen
// in a mirror shows the other's diffuse radiance). Diffuse surfaces and emitters return the
// field's radiance unchanged.
#pragma once

#include "synth/radiance_field.h"

namespace lh::synth {

// Rays per sample spread over a rough surface's reflection cone (2 x 2 strata); a mirror
// (roughness 0) traces one.
constexpr int kGlossyRays = 4;

// Radiance (linear, times the scene's exposure) leaving `hit` towards the viewer, seen along
// the unit direction `dir` (from the viewer to the hit). The glossy jitter is seeded by the
// hit and the direction, so a picture is the same on every run and thread count.
Vec3d viewRadiance(const RayTracer& tracer, const RadianceField& field, const RayHit& hit,
                   const Vec3d& dir);

}  // namespace lh::synth
