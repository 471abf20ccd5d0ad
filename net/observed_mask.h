// Observed-content masks (docs/conventions.md#metrics) for data sets that ship none, computed
// from what they do ship: the first surface each envmap pixel sees (env_K_pos.exr) and the
// reference view's z-depth (ref_depth.exr). Torch-free.
//
// The definition is the one `lighthouse synth` applies with its ray tracer
// (synth/scene_render.cpp, visibleFrom): a pixel is observed when its first-hit point lies in
// front of the reference camera, projects inside the reference image, and nothing lies
// between the camera and it. Without the scene, "nothing in between" is read off the depth
// map: the point is hidden when it is farther than the surface the reference camera sees at
// that pixel, by more than the tolerance. A point nearer than the depth map is not hidden
// (the ray tracer would see it too); it happens at silhouettes, where a pixel's depth is the
// background behind a sub-pixel edge.
#pragma once

#include "core/camera.h"
#include "image/image.h"

#include <cstdint>
#include <vector>

namespace lh::net {

// How much farther than the depth map a point may be and still count as seen, in scene
// units: relative * depth + absolute. The defaults (2% + 2 cm) cover a depth map's sampling
// of slanted surfaces at 320x240 and the half-float rounding of the files.
struct DepthTolerance {
    double relative = 0.02;
    double absolute = 0.02;  // scene units (metres in dev_cycles)
};

// One byte per envmap pixel, row-major, 1 = observed. `positions` holds world (x, y, z) of
// each envmap pixel's first hit in R, G, B; a non-finite position (no hit) is not observed.
// `refDepth` is the reference view's z-depth along its optical axis (channel R; a grey EXR
// reads as R = G = B), the size of `reference`; a non-finite or non-positive depth (no
// surface) hides nothing. Throws InputError if refDepth's size differs from the camera's.
std::vector<std::uint8_t> observedMaskFromDepth(const ImageRGB& positions,
                                                const PinholeCamera& reference,
                                                const ImageRGB& refDepth,
                                                const DepthTolerance& tolerance = {});

}  // namespace lh::net
