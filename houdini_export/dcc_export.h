// Exporting a lighting volume for Blender or Houdini.
//
// The export is a directory:
//   level_<k>.vdb   one file per level k (0 = coarsest), each holding
//                   `density`  FloatGrid, fog volume: extinction sigma, per metre
//                   `emission` Vec3SGrid, colour vector type: sigma * radiance (premultiplied)
//                   `color` (Blender) / `Cd` (Houdini) Vec3SGrid, colour vector type: radiance
//                   with the level's shell only (voxels under finer levels removed, shells.h)
//                   and transforms rotated into the program's axes (dcc_convention.h);
//   mpi.vdb         only when the volume came with an MPI (a predicted volume): its planes,
//                   `mpi_rgb_P<d>` / `mpi_alpha_P<d>`, placed in the program's axes; import
//                   restores the MPI from it (the DCC scripts do not render it);
//   manifest.json   program, axes, levels, files, what was clamped, a checksum of every grid
//                   (grid_checksum.h: import tells from them which grids were edited) and an
//                   export id that every file of the export carries too; marks the directory
//                   as an export so that `lighthouse import` recognises it.
// One file per level because a Blender volume object renders all grids of its file with one
// material and one step size, and Houdini's File SOP gives each file's grids the same names:
// uniform names per file let one shader serve every level.
#pragma once

#include "houdini_export/dcc_convention.h"
#include "vdb/lighting_volume.h"
#include "vdb/mpi.h"

#include <string>
#include <vector>

namespace lh {

struct DccExportOptions {
    Dcc dcc = Dcc::Blender;
    // Every stored value (density, emission and radiance components) is kept at or below this,
    // so that half-precision renderers do not overflow to infinity.
    float maxValue = kDccMaxValue;
    // An existing export at the output is refused unless this is set (`export --force`): the
    // user may have edited it in Blender or Houdini.
    bool replaceExisting = false;
};

// What the value limits changed, per export.
struct DccClampReport {
    std::size_t densityClamped = 0;   // voxels whose sigma was lowered
    std::size_t radianceClamped = 0;  // voxels whose radiance was lowered
    std::size_t nowTranslucent = 0;   // of densityClamped: optical depth per voxel fell below 10
    bool changedAnything() const { return densityClamped || radianceClamped; }
};

struct DccExportReport {
    std::vector<std::string> files;         // written level files, coarsest first
    std::vector<std::size_t> activeVoxels;  // per level shell
    std::string mpiFile;                    // the MPI's file, "" when there was no MPI
    DccClampReport clamp;
    std::vector<std::string> warnings;  // one line each, for the CLI to print
};

// Writes the export directory `outDir` atomically: everything goes to a temporary directory
// beside it, which replaces `outDir` only once complete, in one step where the file system
// allows (a process killed at any moment leaves the old export or the new one, whole). The
// temporaries of an export that was killed are removed by the next one. An existing `outDir`
// is replaced only if it is itself an export (holds a manifest.json); otherwise FileError. Throws
// InputError for an invalid volume. `mpi`, if given, is written too (mpi.vdb).
DccExportReport exportForDcc(const LightingVolume& volume, const std::string& outDir,
                             const DccExportOptions& options = {}, const Mpi* mpi = nullptr);

// Clamping rule for one voxel (exposed for tests). The radiance c is clamped to maxValue per
// component; sigma is lowered to at most maxValue / max(1, max component of c) so that the
// emission sigma * c stays below maxValue too. An opaque emitter keeps its radiance (what a
// viewer sees of an opaque voxel is its colour) as long as it stays opaque.
void clampForDcc(float& sigma, openvdb::Vec3s& color, float maxValue, bool& sigmaChanged,
                 bool& colorChanged);

}  // namespace lh
