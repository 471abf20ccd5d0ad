// Emission-absorption integration along one ray through a RenderVolume.
//
// L = integral T(t) sigma(t) colour(t) dt, T(t) = exp(-integral sigma). The ray is split by the
// finest-wins rule into pieces, each marched in its own level's index space. A segment of length
// dt with midpoint values (sigma, emission = sigma * colour) contributes
//   T * emission * (1 - exp(-sigma dt)) / sigma      (-> T * emission * dt as sigma -> 0)
// and multiplies T by exp(-sigma dt): exact for piecewise-constant media, whatever the step.
//
// Where a step is optically thick (sigma dt above maxStepOpticalDepth), the midpoint value no
// longer stands for the step: the radiance comes from its first optical depths, which the
// midpoint does not see (a first-order error in the colour where a lamp meets a wall). Such a
// step is re-integrated in up to kMaxSubsteps equal sub-steps of optical depth near the bound.
// The cost is bounded because the ray terminates within a few optical depths after it.
#pragma once

#include "render/render_volume.h"

#include <limits>

namespace lh {

struct MarchOptions {
    double stepVoxels = 0.5;          // step length, in voxels of the level being marched
    double minTransmittance = 1e-4;   // stop once T drops below this (0: never stop early)
    bool skipEmptySpace = true;       // jump over empty 8^3 bricks with a DDA
    double maxStepOpticalDepth = 0.5; // sub-divide steps thicker than this (sigma * dt)

    // Fine fixed step, thin sub-steps, no skipping, no early stop: the answer other settings
    // are measured against.
    static MarchOptions reference() { return {0.05, 0.0, false, 0.02}; }
    // Throws InputError for non-positive or absurd steps, a threshold outside [0, 1), or a
    // non-positive maxStepOpticalDepth.
    void validate() const;
};

struct RayResult {
    double radiance[3] = {0.0, 0.0, 0.0};  // linear RGB
    double transmittance = 1.0;            // what is left for the (black) space behind
    // Distance at which the transmittance first fell below 1/2: where the ray "hits" the
    // scene (object insertion uses it as the scene's depth). Infinite if it never did.
    double surfaceDistance = std::numeric_limits<double>::infinity();
};

// `dir` must be unit length; t is measured in scene units from `origin`.
constexpr int kMaxSubsteps = 64;  // sub-steps of one optically thick step

RayResult marchRay(const RenderVolume& volume, const Vec3d& origin, const Vec3d& dir,
                   const MarchOptions& options);

}  // namespace lh
