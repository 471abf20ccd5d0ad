// Collapsing a translucent volume into an opaque shell seen from one centre point.
//
// A predicted volume holds its walls as fog: many voxels of low opacity that a ray crosses one
// after another without stopping, so every envmap pays for all of them (about 23 voxels a ray
// on the demo pair). Seen from a centre point c, the medium in one direction amounts to a
// composite colour C (what the ray gathers, black behind the volume included) and an alpha
// A = 1 - T. The shell replaces it by an opaque layer of colour C, 2 x 1.5 voxels deep, each
// voxel letting 1e-4 of the light through, at the depth where the ray from c has gathered half
// of A. Seen from c the envmap is the same up to the lattice; from elsewhere each direction's
// light sits at one depth instead of being spread along the ray, and rays stop at the first
// layer they meet.
//
// Where the depth jumps between neighbouring directions (the edge of an object in front of a
// wall), a ray from another point can pass behind the object's edge into space that c never
// saw. Skirts close those gaps: a voxel behind its own direction's layer is filled when a
// neighbouring voxel's direction sees its layer farther out, so such rays meet a wall instead
// of the black behind the volume.
//
// The medium inside the reference camera's view is kept as it is (where the volume has a
// camera). The photo saw it: it holds the room's observed surfaces, spread over a few voxels in
// depth, and the points where objects are inserted look at it. Collapsed onto one depth per
// direction from c, it shifts with parallax for every other point. Only the medium the camera
// did not see, the completion's fog around and behind it, which is most of what the rays cross,
// becomes the layer.
#pragma once

#include "core/vec.h"
#include "vdb/lighting_volume.h"

namespace lh {

struct RadialShellOptions {
    // Half-width of the layer, in voxels of the level a point lies in: wide enough that a ray
    // crossing it at a slant still stops in it.
    double halfWidthVoxels = 1.5;
    // Directions whose alpha from the centre is below this carry no visible light: left empty.
    double minAlpha = 1e-4;
    // The centre looks along the pixel centres of a cube map of this many pixels per face side.
    int directionsPerFace = 128;
    // Keep the medium inside the view of the volume's reference camera (LightingVolume::
    // refCamera: in front of it and projecting into its image) as it is, and collapse the rest.
    // Ignored for a volume without a reference camera, which is collapsed whole.
    bool keepCameraView = true;

    // Throws InputError for a half-width outside [0.5, 8], a minAlpha outside [0, 1) or
    // directions per face outside [8, 2048].
    void validate() const;
};

// The centre a predicted volume is collapsed around: on the reference camera's axis, a quarter
// of the way into level 1, which spans the depth range the camera sees (vdb/volume_layout.h);
// the camera itself for a one-level layout.
Vec3d defaultShellCentre(const VolumeLayout& layout);

// The shell of `volume` around `centre` (in the volume's frame), on the same layout, with the
// reference camera's view kept as options.keepCameraView says. Needs a volume with a layout
// (predicted volumes); throws InputError otherwise or if the centre lies outside level 0.
// The shell records `centre` as its shellCentre, so that files say they hold a shell.
LightingVolume collapseToShell(const LightingVolume& volume, const Vec3d& centre,
                               const RadialShellOptions& options = {});

// Whether collapseToShell keeps a camera's view of `volume` under `options`: it asks for it and
// the volume has a reference camera.
bool keepsCameraView(const LightingVolume& volume, const RadialShellOptions& options);

// The density (per scene unit) of the shell's opaque layer in a level whose voxels are
// `voxelSize` scene units wide: one voxel of it lets 1e-4 of the light through (older shells:
// 1%).
float shellLayerDensity(double voxelSize);

// Whether `volume` looks like a shell that does not record its centre (LightingVolume::
// shellCentre), as those written before shells recorded it: on a layout, every active voxel
// collapseToShell would have collapsed (outside the reference camera's view, or every voxel
// without a camera) and no finer level hides holds the layer's density, or that of the older
// 1% layer, within 1%, and there is at least one. The network's fog never does: its density varies
// from voxel to voxel. A file whose values were rounded to fewer than 7 mantissa bits, or edited,
// may not be recognised.
bool looksLikeUnmarkedShell(const LightingVolume& volume);

}  // namespace lh
