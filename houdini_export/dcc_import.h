// Reading an export (dcc_export.h), possibly edited in Blender, Houdini or python3-openvdb,
// back into a lighting volume: shells become levels again.
//
// Per level file: `density` (FloatGrid) is required. The radiance is held twice, as the
// emission grid(s) (`emission`, or Blender's `emission_r/g/b`: density x colour, what the DCC
// renders) and as `color` (Blender) / `Cd` (Houdini); the manifest's checksums (dcc_edits.h)
// tell which the user edited, and that one wins:
//   colour edited, emission not        -> colour (emission is then colour x density);
//   otherwise (emission or density edited, or nothing) -> emission: colour = emission / density;
//   both edited and disagreeing        -> emission, what the renderer showed, and one warning
//                                         naming the level, its file and both grids (a warning,
//                                         not an error: the import is what the user saw);
//   one of the two missing             -> the other.
// A manifest without checksums (an older export, or made by hand) gets the emission rule for
// every level and one warning saying so. Transforms are rotated back to lighthouse's
// world frame. Each level's domain is the `lighthouse_domain_min/max` grid metadata (or, if
// an edit dropped it, the active bounding box); the coarsest level's domain also grows to
// every active voxel, so content added outside the volume is kept. Voxels a shell holds under
// a finer level, or a finer level holds outside its domain, are ignored with a warning (finest
// wins would hide them). Covered voxels are then refilled from the finer levels
// (shells.h, fillCoveredFromFiner). An export's MPI (mpi.vdb, when the manifest lists one)
// comes back with the volume.
#pragma once

#include "houdini_export/dcc_convention.h"
#include "vdb/lighting_volume.h"
#include "vdb/mpi.h"
#include "vdb/volume_io.h"

#include <optional>
#include <string>
#include <vector>

namespace lh {

struct DccImportReport {
    std::vector<std::string> warnings;  // one line each, for the CLI's `warning:` lines
    std::vector<std::string> notes;  // what import chose where it had a choice (a level's radiance)
    std::optional<Mpi> mpi;          // the export's MPI, if it carried one
    std::string mpiFile;             // and its file
};

// Throws FileError naming the file (and grid) if `dir` is not an export for `dcc`, the manifest
// is malformed or belongs to other files (their export ids differ), a level file is missing or
// unreadable, or grids have the wrong type or transform. NaN/Inf/negative values of the
// density and of the radiance grid read are replaced (as loadVolume does) and reported in
// `warnings`; with NonFinitePolicy::Reject they are a FileError naming the file and the grid.
LightingVolume importFromDcc(const std::string& dir, Dcc dcc, DccImportReport* report = nullptr,
                             NonFinitePolicy nonFinite = NonFinitePolicy::Sanitise);

}  // namespace lh
