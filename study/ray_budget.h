// Where an envmap's rays spend the marcher's work in a volume. The cell quadrature costs about
// one walk step and a few samples per lattice cell of medium a ray crosses before it stops
// (render/ray_marcher.h), and empty space is skipped, so its time follows how far rays travel
// through medium. This measures that distance per level, in the level's own voxels, split by
// how opaque the medium is, with the share of the light each level gives: a volume of opaque
// walls stops its rays within a few voxels, a fog carries them through every level.
#pragma once

#include "render/render_volume.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace lh {

struct RayBudgetOptions {
    int points = 8;                // query points in free space (render/free_space.h)
    int width = 120, height = 60;  // rays per point: one per pixel of an envmap of this size
    uint64_t seed = 1;             // of the query points
    // A ray stops counting once its transmittance is below this: the threshold at which the
    // fastest settings of bench-envmap stop their rays.
    double minTransmittance = 1e-2;
    double stepVoxels = 0.25;  // sampling step along the ray, in voxels of the level crossed

    void validate() const;  // throws InputError
};

// Opacity classes of the medium a ray crosses, by the alpha of one voxel of its level,
// alpha = 1 - exp(-sigma x voxel size): faint fog, fog, translucent, dense, opaque.
constexpr int kAlphaClasses = 5;
constexpr std::array<double, kAlphaClasses + 1> kAlphaClassEdges = {0.0, 0.03, 0.15, 0.5, 0.9, 1.0};

// Transmittance classes of the rays that leave the volume before they stop: the first class
// holds everything from the threshold (RayBudgetOptions::minTransmittance) up to 0.05.
constexpr std::array<double, 5> kLeftEdges = {0.01, 0.05, 0.1, 0.3, 1.0};
constexpr int kLeftClasses = int(kLeftEdges.size()) - 1;

struct RayBudgetLevel {
    double voxelSize = 0;  // scene units (cube root of the voxel volume)
    // Fraction of rays that cross some of this level's domain while still counting (their
    // transmittance above the threshold where the level's part of them begins).
    double raysReaching = 0;
    // Voxels of medium (density > 0) crossed per ray while counting, mean over all rays, by
    // alpha class.
    std::array<double, kAlphaClasses> mediumVoxels{};
    double lightShare = 0;  // fraction of all the rays' radiance (sum of RGB) gathered here
    double mediumVoxelsTotal() const;
};

struct RayBudget {
    std::vector<RayBudgetLevel> levels;  // coarsest first, as in the volume
    int points = 0;                      // query points
    int rays = 0;                        // rays traced: points x width x height
    double raysStopped = 0;  // fraction of rays whose transmittance fell below the threshold
    // Fraction of all rays that leave the volume with a transmittance in [edge k, edge k + 1)
    // of kLeftEdges: how nearly closed the rest are.
    std::array<double, kLeftClasses> raysLeaving{};
    double mediumVoxelsPerRay() const;  // over all levels and classes
};

// At options.points query points in free space; deterministic for a seed. Throws InputError
// for bad options or a volume without free space.
RayBudget measureRayBudget(const RenderVolume& volume, const RayBudgetOptions& options);
// At the given points (options.points and seed unused).
RayBudget measureRayBudget(const RenderVolume& volume, const std::vector<Vec3d>& points,
                           const RayBudgetOptions& options);

// A Markdown table, one row per level, then a line of totals.
std::string rayBudgetMarkdown(const RayBudget& budget, const RayBudgetOptions& options);

}  // namespace lh
