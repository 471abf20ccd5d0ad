// Rendering equirectangular environment maps (docs/conventions.md#envmap-layout) from a lighting
// volume.
#pragma once

#include "image/image.h"
#include "render/ray_marcher.h"

namespace lh {

struct EnvmapOptions {
    int width = 240;  // W = 2 H
    int height = 120;
    MarchOptions march;
    // Radiance behind the volume (linear RGB): each pixel adds transmittance x background.
    // Black, the convention, by default; the evaluation's baselines fill what an MPI leaves
    // unseen with grey or with the photo's mean colour.
    float background[3] = {0.f, 0.f, 0.f};
    // Find where each ray first meets the medium once per envmap (render/first_medium.h) and
    // start its march there. Same answers (up to rounding), fewer instructions (measured in
    // docs/performance.md); cell quadrature only (fixed steps start from the origin).
    bool startAtFirstMedium = true;

    // Throws InputError unless W = 2 H >= 2 and the background is finite and non-negative,
    // ResourceError above kMaxEnvmapPixels.
    void validate() const;
};

// Bound on envmap size: 2^27 pixels is 1.5 GiB of float RGB.
constexpr long long kMaxEnvmapPixels = 1LL << 27;

// Incident radiance at `position` (world frame) from every direction. Rows run in parallel.
ImageRGB renderEnvmap(const RenderVolume& volume, const Vec3d& position,
                      const EnvmapOptions& options = {});

}  // namespace lh
