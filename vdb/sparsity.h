// Storing only what a scene needs: error-bounded sparsity of a lighting volume.
//
// One bound, `tau`, decides every drop: the largest change of linear radiance (display white =
// 1, the peak of docs/conventions.md's PSNR) that pruning may cause in any envmap pixel, i.e. along
// any ray. A per-voxel bound is not enough: a ray crosses hundreds of voxels, and in the dense
// low-alpha fog the network predicts every one of them is "thin", so dropping each voxel below
// tau lets the errors add up along the ray. The derivation (emission-absorption, premultiplied
// trilinear sampling, docs/conventions.md#interpolation):
//   L = integral T e dt, e = sigma * colour, T = exp(-integral sigma). Changing sigma by
//   d_sigma(x) and emission by d_e(x) changes L by at most
//       integral (|d_e| + C |d_sigma|) dt  <=  rayLength * max_x (|d_e| + C |d_sigma|),
//   where C is the brightest colour of the volume (the radiance behind any point is at most C)
//   and rayLength is the longest segment a ray can run inside the volume (the diagonal of its
//   bounding box, scene units). Trilinear weights sum to 1, so a pointwise bound on the voxel
//   values is a pointwise bound on the field.
// Each of the three mechanisms gets a third of tau, i.e. a field bound
//   eps = tau / (3 rayLength)   (radiance per scene unit):
//   * thin voxels (and tiles) with sigma * C <= eps are deactivated (dropping one changes sigma
//     by sigma and emission by at most sigma * C, and |d_e| <= C d_sigma along a ray);
//   * where a coarser level reproduces a finer one (|e_f - e_c| + C |sigma_f - sigma_c| <= eps at
//     every fine voxel centre, both sampled as the renderer does), the finer level's domain
//     shrinks to the bounding box of the voxels that differ (plus one voxel), or the level goes
//     away when none differ. A domain is a box because finest-wins is decided by domains: a
//     hole in a finer level would read as empty space, not as the coarser level;
//   * nodes whose values agree within eps / (6 C) (density) and eps / (6 sigma_max) (colour)
//     collapse into tiles (tools::prune moves a value by at most twice its tolerance), and
//     inactive leaves are freed (tools::pruneInactive); colour is kept only where density is.
// Half precision on disk adds a relative error of 2^-11 per value on top (about 1e-3 C at most
// along a ray), which the studies measure by rendering the half file read back.
// The bound is a worst case (it ignores the attenuation T); the envmap error that results is
// measured, not assumed: see measureMemoryAgainstError (study/memory_error.h) and
// `lighthouse bench-sparsity`. PSNR is taken on sRGB-encoded values, whose slope is at most
// 12.92, so PSNR against the unpruned envmaps >= -20 log10(12.92 tau).
#pragma once

#include "vdb/lighting_volume.h"
#include "vdb/volume_io.h"

#include <string>

namespace lh {

struct SparsityOptions {
    // Per-ray (envmap pixel) error bound, linear radiance (white 1). 1e-4: PSNR against the
    // unpruned envmaps >= 57.8 dB in the worst case, so at most 0.1 dB lost against ground
    // truth for volumes up to 19 dB (predicted ones reach ~15); measured, no tau up to 0.3
    // changed the oracle, example or predicted volumes more than another (docs/performance.md).
    double tau = 1e-4;
    bool dropThinVoxels = true;      // deactivate voxels below the density bound
    bool dropReproducedFine = true;  // shrink or drop finer levels the coarser ones reproduce
    bool pruneTiles = true;          // collapse near-constant nodes into tiles
    int maxLevels = 0;               // > 0: keep only the coarsest maxLevels levels

    // Throws InputError unless tau is in [0, 1] and maxLevels >= 0.
    void validate() const;
};

struct SparsityStats {
    openvdb::Index64 activeBefore = 0,
                     activeAfter = 0;  // active density voxels (tiles count fully)
    openvdb::Index64 memoryBefore = 0, memoryAfter = 0;  // bytes of both grids in memory
    openvdb::Index64 thinVoxelsDropped = 0;              // below the density/emission bound
    openvdb::Index64 reproducedVoxelsDropped = 0;        // outside a shrunken finer domain
    int levelsDropped = 0;                               // reproduced entirely, or beyond maxLevels
    double rayLength = 0;   // longest ray segment inside the volume, scene units
    double maxColour = 0;   // brightest colour component where density is
    double fieldBound = 0;  // eps = tau / (3 rayLength), radiance per scene unit
};

// The quantities the bound is derived from (see the top of this file), for a volume and tau.
struct SparsityBound {
    double rayLength = 0;   // diagonal of the world bounding box of all levels, scene units
    double maxColour = 0;   // brightest colour component over voxels with density
    double fieldBound = 0;  // eps = tau / (3 rayLength), radiance per scene unit
    // Largest density a thin voxel may have to be dropped: eps / C (infinite if C = 0: a black
    // volume renders black whatever is dropped).
    double thinDensity() const;
};
SparsityBound sparsityBound(const LightingVolume& volume, double tau);

// Bytes of a volume in memory, split by what they pay for (OpenVDB's Tree::memUsage summed by
// node kind): the root and the fixed upper nodes (a 32^3 and a 16^3 table per populated
// 4096^3 / 128^3 region, whatever they hold), and the 8^3 leaves, for density and colour.
struct MemoryBreakdown {
    openvdb::Index64 densityUpper = 0, densityLeaves = 0, colourUpper = 0, colourLeaves = 0;
    openvdb::Index64 leafCount = 0;     // density leaves
    openvdb::Index64 activeVoxels = 0;  // active density voxels (tiles count fully)
    openvdb::Index64 total() const {
        return densityUpper + densityLeaves + colourUpper + colourLeaves;
    }
    // An estimate, not a representation this project has: what a packed store of only the
    // active voxels would take (per 8^3 block: a 12-byte origin, a 64-byte active mask and an
    // 8-byte index entry; per active voxel: sigma and RGB as 4 floats). Tiles count as all
    // their voxels, so it is an upper bound for such a store.
    openvdb::Index64 packedBytes() const { return leafCount * (12 + 64 + 8) + activeVoxels * 16; }
};
MemoryBreakdown memoryBreakdown(const LightingVolume& volume);

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

// Writes a sparsified volume Blosc-compressed, optionally as half floats (values above
// kHalfSafeMax clamped, vdb/volume_io.h; the relative rounding error of every stored value is
// then at most 2^-11), and optionally rounded to `mantissaBits` first (0: not rounded;
// vdb/mantissa_rounding.h, relative error at most 2^-(bits+1)).
VolumeSaveReport saveSparseVolume(const std::string& path, const LightingVolume& volume,
                                  bool halfPrecision, int mantissaBits = 0);

// Active density voxels of every level (tiles count their voxels).
openvdb::Index64 activeDensityVoxels(const LightingVolume& volume);

}  // namespace lh
