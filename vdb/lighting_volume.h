// The lighting volume: an emission-absorption medium stored as nested OpenVDB grids.
// Each level is a FloatGrid `density` (extinction sigma, per scene unit) and a Vec3SGrid
// `color` (linear RGB radiance) sharing one affine index->world transform. Which level is
// finer is decided by voxel size, never by position in a list or file.
#pragma once

#include "core/camera.h"
#include "vdb/volume_layout.h"

#include <openvdb/openvdb.h>

#include <functional>
#include <optional>
#include <vector>

namespace lh {

// Medium at one point.
struct MediumSample {
    float sigma = 0.f;                    // extinction, per scene unit
    openvdb::Vec3s color{0.f, 0.f, 0.f};  // linear radiance
};

struct VolumeLevel {
    openvdb::FloatGrid::Ptr density;
    openvdb::Vec3SGrid::Ptr color;
    // Index-space voxels (inclusive) the level covers: where it is the finest level, it defines
    // the medium, active or not. For our files the layout box; for foreign files the active
    // voxel bounding box.
    openvdb::CoordBBox domain;

    const openvdb::math::Transform& transform() const { return density->transform(); }
    double voxelVolume() const { return transform().voxelVolume(); }  // scene units^3
    // Corners of the domain's outer voxel faces in world space, axis-aligned bounds.
    WorldBox worldBounds() const;
    // True if the world point lies inside the domain's outer voxel faces.
    bool containsWorld(const Vec3d& p) const;
};

class LightingVolume {
public:
    std::vector<VolumeLevel> levels;         // coarsest first; finest last
    std::optional<VolumeLayout> layout;      // set when the volume follows the nested layout
    std::optional<PinholeCamera> refCamera;  // set when known (predicted volumes)
    // Set on a shell (render/radial_shell.h): the point, in scene units, its medium was
    // collapsed around. Collapsing a shell again cannot bring back what the first one dropped.
    std::optional<Vec3d> shellCentre;

    // Empty levels of a layout with transforms and domains set.
    static LightingVolume fromLayout(const VolumeLayout& layout);

    // Fills level `k` by evaluating `field` at every voxel centre of its domain (in parallel).
    // Voxels with sigma == 0 stay inactive, so empty space costs nothing.
    void fillLevel(int k, const std::function<MediumSample(const Vec3d& world)>& field);

    // Orders levels coarsest first (by voxel volume) and sets `level` metadata, the fog-volume
    // class and the colour vector type. Grids keep their names (a foreign file's `density`
    // stays `density`); saveVdb writes the density_L<k> / color_L<k> convention. Throws
    // InputError if two levels have the same voxel volume.
    void normaliseLevels();

    // Throws InputError if a level is malformed (missing grid, non-linear transform, density
    // and colour transforms differ, empty domain).
    void validate() const;

    openvdb::Index64 activeVoxelCount() const;
    openvdb::Index64 memoryBytes() const;
};

// Index of the finest level whose domain contains the world point (the level that defines the
// medium there), or -1 outside every level. Levels must be ordered coarsest first.
int finestLevelAt(const LightingVolume& volume, const Vec3d& world);

// "a FloatGrid", "a Vec3SGrid", or "a <value type> grid" for messages.
std::string gridKind(const openvdb::GridBase& grid);

// Grid names of level k on disk.
std::string densityGridName(int level);
std::string colorGridName(int level);

}  // namespace lh
