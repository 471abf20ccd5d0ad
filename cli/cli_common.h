// Small helpers shared by the subcommands: parsing user values and loading volumes with
// warnings printed once.
#pragma once

#include "core/vec.h"
#include "vdb/lighting_volume.h"
#include "vdb/volume_io.h"

#include <string>
#include <vector>

namespace lh::cli {

// "X,Y,Z" (or space separated) -> finite point; throws InputError naming `what`.
Vec3d parsePoint(const std::string& text, const std::string& what);
// A text file with one point per line ("x y z" or "x,y,z"; '#' starts a comment).
std::vector<Vec3d> readPointsFile(const std::string& path);
// "WxH" -> (W, H); throws InputError.
void parseSize(const std::string& text, int& width, int& height);
// Loads a volume, printing sanitising warnings to stderr.
LightingVolume loadVolumeForCli(const std::string& path, bool strict);
// The same, with the file's MPI when it holds one (commands that pass the MPI on).
VolumeFile loadVolumeFileForCli(const std::string& path, bool strict);
// After a save: one "warning:" line on stderr when values were clamped to fit half precision,
// ending with `hint` in parentheses (the flag that asked for halves, or how to avoid them).
void warnOfHalfClamping(const VolumeSaveReport& saved, const std::string& hint);
// One "warning:" line on stderr for each point outside every level of `volume`: its envmap
// sees the volume from outside (a point in the wrong frame or units, most often).
void warnOfPointsOutside(const LightingVolume& volume, const std::vector<Vec3d>& points);
// "out.exr", 3 -> "out_003.exr"
std::string numberedPath(const std::string& path, int index);
// Replaces the extension: ("a/b.exr", ".png") -> "a/b.png".
std::string withExtension(const std::string& path, const std::string& extension);
// Throws InputError "output 'PATH' must end in .vdb (WHAT)" unless PATH's extension is .vdb in
// any case (OpenVDB reads the file whatever its name, but the tools that list and open .vdb
// files go by the extension). Commands call it before any work. `what` says what the command
// writes, e.g. "the lighting volume".
void requireVdbOutput(const std::string& path, const std::string& what);

}  // namespace lh::cli
