// The bundled example: a procedural room built by code (no binary blob), used by the README's
// main job and by tests until predicted volumes exist. A 5 m x 2.7 m x 7.5 m room around the
// reference camera: red wall at -x, green wall with a bright window at +x, a warm emissive
// ceiling panel, a grey back wall ahead, an orange table in front of the camera, and a blue
// cube and a yellow ball close to the camera (in the finest levels).
#pragma once

#include "core/camera.h"
#include "vdb/lighting_volume.h"

namespace lh {

// The room's medium at a world point (metres, OpenCV axes: +y is down).
MediumSample exampleRoomMedium(const Vec3d& p);

// The room sampled into `layout` (default: s0 from a far depth of 7 m, 5 x 64^3), with
// 2x2x2 supersampling per voxel (box filter on sigma and premultiplied emission).
LightingVolume makeExampleVolume(int levels = 5, int resolution = 64);

// Reference camera (320x240, 60 degree horizontal field of view) at the origin, plus a
// second camera 0.1 m to its right and a near/far range matching the room.
CamerasFile exampleCameras();

}  // namespace lh
