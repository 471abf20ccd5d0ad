// Storing only what a scene needs (issue 7): error-bounded sparsity of a lighting volume.
//
// One bound, `tau`, in display radiance units (PSNR's peak is 1, CONVENTIONS.md), decides
// every drop, so that what is removed changes no envmap ray by more than about tau per voxel
// it crosses:
//   * voxels whose opacity sigma*h and emitted radiance sigma*max(colour)*h (h = voxel edge)
//     are both below tau are deactivated: they could dim or brighten a ray by at most tau;
//   * where a coarser level reproduces a finer one (|sigma_f - sigma_c| h_f and
//     |emission_f - emission_c| h_f below tau at every voxel centre, emission = sigma * colour
//     sampled trilinearly, as the renderer does), the finer level's domain shrinks to the
//     bounding box of the voxels that differ (plus one voxel), or the level goes away when
//     none differ. A domain is a box because finest-wins is decided by domains: a hole in a
//     finer level would read as empty space, not as the coarser level;
//   * nodes whose values agree within the bound collapse into tiles (tools::prune), and
//     inactive leaves are freed (tools::pruneInactive); colour is kept only where density is.
// The envmap error that results is measured, not assumed: see measureMemoryAgainstError
// (render/speed_error.h) and `lighthouse bench-sparsity`.
#pragma once

#include "vdb/lighting_volume.h"
#include "vdb/volume_io.h"

#include <string>

namespace lh {

struct SparsityOptions {
    double tau = 1e-3;              // per-voxel error bound, display radiance units (peak 1)
    bool dropThinVoxels = true;     // deactivate voxels below the density/emission bound
    bool dropReproducedFine = true; // shrink or drop finer levels the coarser ones reproduce
    bool pruneTiles = true;         // collapse near-constant nodes into tiles
    int maxLevels = 0;              // > 0: keep only the coarsest maxLevels levels

    // Throws InputError unless tau is in [0, 1] and maxLevels >= 0.
    void validate() const;
};

struct SparsityStats {
    openvdb::Index64 activeBefore = 0, activeAfter = 0;  // active density voxels (tiles count fully)
    openvdb::Index64 memoryBefore = 0, memoryAfter = 0;  // bytes of both grids in memory
    openvdb::Index64 thinVoxelsDropped = 0;   // below the density/emission bound
    openvdb::Index64 reproducedVoxelsDropped = 0;  // outside a shrunken finer domain
    int levelsDropped = 0;                    // reproduced entirely, or beyond maxLevels
};

// A sparsified deep copy of `volume` (the input is untouched). Throws InputError for bad
// options or a malformed volume.
LightingVolume sparsify(const LightingVolume& volume, const SparsityOptions& options,
                        SparsityStats* stats = nullptr);

// Levels a nested layout needs for a scene seen by the reference camera between depths
// `near` and `far` (scene units): level k spans z in [0, s0 / 2^k] with s0 = 2 min(far, 20),
// so once s0 / 2^k < near the level lies in front of everything the camera sees and holds
// only empty space. Returns the count of levels with s0 / 2^k >= near, in [1, maxLevels].
// Throws InputError unless 0 < near <= far are finite.
int levelsForDepthRange(double near, double far, int maxLevels = 5);

// Largest values a 16-bit half stores (65504) minus a margin: save clamps to it.
constexpr float kHalfSafeMax = 65000.f;

// Writes a sparsified volume Blosc-compressed, optionally as half floats. With half
// precision, values above kHalfSafeMax are clamped first (a density of 65000 per scene unit
// is opaque over any voxel above 1 mm; radiance above it saturates) so nothing overflows to
// Inf; the relative rounding error of every stored value is then at most 2^-11.
void saveSparseVolume(const std::string& path, const LightingVolume& volume, bool halfPrecision);

// Active density voxels of every level (tiles count their voxels) and bytes in memory.
openvdb::Index64 activeDensityVoxels(const LightingVolume& volume);

}  // namespace lh
