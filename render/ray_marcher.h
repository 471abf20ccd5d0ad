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
//
// Cell quadrature (cellNodes > 0, the default): instead of fixed steps, the ray is cut where it
// crosses the lattice planes of the trilinear interpolation, so that inside each piece sigma and
// emission are smooth (cubic in t) and the kinks of trilinear interpolation fall on piece
// boundaries. Each piece is split into cellNodes sub-segments of Gauss-Legendre weight, each
// taking the medium at its Gauss node: the optical depth of a piece is then exact for
// polynomials of degree 2 cellNodes - 1 (exact for trilinear media with 2 nodes), and with a
// constant colour so is the radiance. Lattice cells whose eight corners are all empty are
// skipped without sampling (exact: the field is zero inside them), and so is everything outside
// the box of a level's occupied cells and, inside a brick, outside the box of its occupied
// cells: the walk visits only cells that can hold medium. Inside a piece the
// sub-segments hold the medium constant, which misplaces light between them where the colour
// changes (exact for a constant colour, however thick). That error grows with the optical
// depth the piece shows (tau times the transmittance in front of it) and with how bright it
// is, so a piece is halved (recursively) while
//   tau * T * brightness / typicalRadiance > cellRefineBound * cellNodes,
// brightness being the brightest colour channel at its nodes and typicalRadiance the scene's
// (RenderVolume::typicalRadiance). Where a ray meets a bright surface the parts get short
// where the density is; dim walls and the light hidden behind the first optical depths are
// not refined for nothing. Measured on an oracle volume, weighing by brightness gives 10x
// less error relative to the mean radiance for the same time (docs/performance.md).
//
// Early stop: a ray stops once its transmittance T falls below minTransmittance, and what is left
// of it sees an opaque surface of the colour where it stopped (T x emission / sigma is added,
// T becomes 0). The medium behind a point where the light is nearly all absorbed is most often
// more of the same surface, so the estimate errs by T times a difference of colours, where
// dropping the rest errs by T times the whole radiance: on the demo pair's prediction, stopping
// at 1e-3 with the estimate errs as much as stopping at 1e-4 without it (4.2e-4 against
// 4.0e-4 of the mean radiance) and renders 9% more envmaps a second (docs/performance.md).
#pragma once

#include "render/render_volume.h"

#include <limits>

namespace lh {

struct MarchOptions {
    double stepVoxels = 0.5;         // step length, in voxels of the level being marched
    double minTransmittance = 1e-3;  // stop once T drops below this, the rest taking the
                                     // colour where it stopped (0: never stop early)
    bool skipEmptySpace = true;      // jump over empty 8^3 bricks with a DDA
    double maxStepOpticalDepth =
        0.5;                       // fixed steps: sub-divide steps thicker than this (sigma * dt)
    int cellNodes = 2;             // Gauss nodes per lattice cell (1-3); 0: fixed steps of
                                   // stepVoxels (cell quadrature ignores stepVoxels and
                                   // always skips empty bricks and cells)
    double cellRefineBound = 1.0;  // cells: halve a piece above this (optical depth per node
                                   // x transmittance x brightness / typical radiance); the
                                   // default keeps envmap RMSE below 1e-3 of the mean radiance
    double surfaceTransmittance = 0.5;  // RayResult::surfaceDistance is where T falls below this

    // Fine fixed step, thin sub-steps, no skipping, no early stop: the answer other settings
    // are measured against.
    static MarchOptions reference() { return {0.05, 0.0, false, 0.02, 0}; }
    // Throws InputError for non-positive or absurd steps, a threshold outside [0, 1), a
    // non-positive maxStepOpticalDepth or cellRefineBound, a surfaceTransmittance outside (0, 1),
    // or cellNodes outside [0, 3].
    void validate() const;
};

struct RayResult {
    double radiance[3] = {0.0, 0.0, 0.0};  // linear RGB
    double transmittance = 1.0;            // what is left for the (black) space behind: 0
                                           // after an early stop (MarchOptions)
    // Distance at which the transmittance first fell below MarchOptions::surfaceTransmittance
    // (1/2 by default): where the ray "hits" the scene (object insertion uses it as the scene's
    // depth). Infinite if it never did.
    double surfaceDistance = std::numeric_limits<double>::infinity();
};

// `dir` must be unit length; t is measured in scene units from `origin`.
constexpr int kMaxSubsteps = 64;  // sub-steps of one optically thick step

RayResult marchRay(const RenderVolume& volume, const Vec3d& origin, const Vec3d& dir,
                   const MarchOptions& options);
// The same for many rays from one origin (RenderVolume::rayOrigin, computed once). With the
// cell quadrature, `tStart` (scene units) may name a distance before which the ray meets no
// medium (render/first_medium.h): the walks start there, with the same answer up to rounding.
// Fixed steps ignore it (their steps are laid from where each level's piece begins).
RayResult marchRay(const RenderVolume& volume, const RenderVolume::RayOrigin& origin,
                   const Vec3d& dir, const MarchOptions& options, double tStart = 0.0);

}  // namespace lh
