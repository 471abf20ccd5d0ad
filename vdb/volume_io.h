// Reading and writing lighting volumes and MPIs as .vdb files.
//
// File metadata: `lighthouse_format_version` (int), `lighthouse_layout` (JSON, when the volume
// follows the nested layout), `lighthouse_ref_camera` (JSON camera, when known). Grid metadata:
// `level` (int) and `lighthouse_domain_min/max` (the index box the level covers).
//
// Loading is grid-aware: every FloatGrid named `density` or `density<suffix>` paired with a
// Vec3SGrid `color<suffix>` (or `Cd<suffix>`) is one level, whatever its transform; which level
// is finer is decided by voxel size. A Blender-style file with just `density` and `color`
// loads as a one-level volume.
//
// Non-finite values (policy, applied on load and reported as warnings): density NaN -> 0,
// +Inf -> kOpaqueDensity, negative -> 0; colour NaN -> 0, +Inf -> kMaxRadiance, negative
// components -> 0. With NonFinitePolicy::Reject the load fails instead, naming file and grid.
#pragma once

#include "vdb/lighting_volume.h"
#include "vdb/mpi.h"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace lh {

constexpr int kVolumeFormatVersion = 1;
constexpr float kOpaqueDensity = 1e15f;  // per scene unit: opaque over any step above 1e-13
constexpr float kMaxRadiance = 1e15f;    // linear radiance ceiling for sanitised +Inf

enum class NonFinitePolicy { Sanitise, Reject };

struct VolumeLoadOptions {
    NonFinitePolicy nonFinite = NonFinitePolicy::Sanitise;
};

// Largest values a 16-bit half stores (65504) minus a margin: saving in half precision clamps
// the volume's densities and radiance components to it, so nothing overflows to Inf (a density
// of 65000 per scene unit is opaque over any voxel above 1 mm; radiance above it saturates).
constexpr float kHalfSafeMax = 65000.f;

struct VolumeSaveOptions {
    bool halfPrecision = false;  // store float values as 16-bit halves on disk
    // 0: values as they are; N in [1, 22] (at most 9 with halfPrecision): every value of the
    // volume rounded to N mantissa bits first (vdb/mantissa_rounding.h), relative error at
    // most 2^-(N+1), in exchange for a smaller file; the MPI's values too.
    int mantissaBits = 0;
};

// What saving changed, for the caller to report.
struct VolumeSaveReport {
    std::size_t valuesClampedToHalf = 0;  // voxels and tiles whose value exceeded kHalfSafeMax
};

// Writes the volume (and optionally an MPI) to `path` atomically, Blosc-compressed.
VolumeSaveReport saveVdb(const std::string& path, const LightingVolume* volume, const Mpi* mpi,
                         const VolumeSaveOptions& options = {});
inline VolumeSaveReport saveVolume(const std::string& path, const LightingVolume& volume,
                                   const VolumeSaveOptions& options = {}) {
    return saveVdb(path, &volume, nullptr, options);
}
// "N value(s) above 65000 were clamped to fit half precision", or "" when none were.
std::string halfClampWarning(const VolumeSaveReport& report);

// Loads the lighting volume of a .vdb file. Throws FileError naming the file (and grid) if
// the file is not a VDB, has no density/colour pair, has wrong grid types or non-affine
// transforms, or (with Reject) holds NaN/Inf. `warnings`, if given, receives what was sanitised.
// An MPI the file holds is not read (vdb/grid_selection.h): loadVolumeFile reads both.
LightingVolume loadVolume(const std::string& path, std::vector<std::string>* warnings = nullptr,
                          const VolumeLoadOptions& options = {});

// A file's lighting volume and, when it holds one (a predicted volume), its MPI, from one read.
struct VolumeFile {
    LightingVolume volume;
    std::optional<Mpi> mpi;
};
VolumeFile loadVolumeFile(const std::string& path, std::vector<std::string>* warnings = nullptr,
                          const VolumeLoadOptions& options = {});

// Loads the MPI stored in a file written by saveVdb.
Mpi loadMpi(const std::string& path);

}  // namespace lh
