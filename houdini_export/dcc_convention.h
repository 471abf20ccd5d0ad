// What Blender and Houdini expect of a lighting volume: their world axes, grid names and the
// value range their renderers handle. Lighthouse's world is the reference camera's OpenCV frame
// (+x right, +y down, +z forward, scene units = metres); both programs use metres too, so the
// conversion is a pure rotation (no scale):
//   Blender (Z-up, right-handed, "front" looks along +Y):  X = x, Y = z,  Z = -y
//   Houdini (Y-up, right-handed, cameras look along -Z):   X = x, Y = -y, Z = -z
#pragma once

#include "core/vec.h"

#include <string>

namespace lh {

enum class Dcc { Blender, Houdini };

struct DccConvention {
    Dcc dcc = Dcc::Blender;
    std::string name;       // "blender" or "houdini"
    Mat3d worldToDcc;       // rotation, lighthouse world -> DCC world (column vectors)
    std::string axesText;   // human-readable form of worldToDcc, for manifests and messages
    std::string colorGrid;  // radiance grid name: "color" (Blender) or "Cd" (Houdini)
    // Premultiplied emission as three FloatGrids `emission_r/g/b` (Blender) instead of one
    // Vec3SGrid `emission` (Houdini). Blender 3.4's Cycles misreads Vec3 grids through the
    // Attribute node (measured on an opaque block of radiance 1: 2.8 inside, up to 5 at its
    // edges), while float grids render it at 1.00; see houdini_export/README.md.
    bool splitEmission = false;
    // Index-space shift written into every transform. Blender 3.4 places the value of voxel
    // (i, j, k) at the centre of the cell from index (i, j, k) to (i+1, j+1, k+1), half a voxel
    // off OpenVDB's convention (the value sits at the index point); measured with Cycles on a
    // block symmetric about the horizon, which lands 0.7 px off-centre without the shift.
    // Exporting with a -0.5 shift puts every voxel where lighthouse has it; import undoes it.
    double indexShift = 0.0;
};

// Grid names shared by both programs. `emission` = sigma * colour (premultiplied, per scene
// unit) is what the DCC material renders: interpolating it, not `color`, keeps surfaces at
// full brightness (docs/conventions.md#interpolation).
inline const char* const kDccDensityGrid = "density";
inline const char* const kDccEmissionGrid = "emission";
inline const char* const kDccEmissionChannelGrids[3] = {"emission_r", "emission_g", "emission_b"};

// Largest finite IEEE half: Cycles stores volume grids at half precision by default.
constexpr float kDccMaxValue = 65504.f;

// Export directory layout: one .vdb per level plus a JSON manifest.
constexpr int kDccExportVersion = 1;
inline const char* const kDccManifestName = "manifest.json";
std::string dccLevelFileName(int level);  // "level_0.vdb"
inline const char* const kDccMpiFileName = "mpi.vdb";

DccConvention dccConvention(Dcc dcc);
// "blender" / "houdini" (case-insensitive) -> Dcc; throws InputError naming `what`.
Dcc parseDcc(const std::string& text, const std::string& what);

}  // namespace lh
