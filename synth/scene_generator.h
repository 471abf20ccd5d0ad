// Procedural indoor scenes shaped after the evaluation rooms: 3-8 m wide (x), 4-10 m deep (z),
// 2.4-3.5 m high, with textured walls, floor and ceiling, 1-3 windows showing HDR panoramas,
// emissive panels and lamps, 3-10 pieces of furniture, and a stereo rig standing in the back
// half of the room looking down its depth. Deterministic by seed.
#pragma once

#include "core/camera.h"
#include "synth/scene.h"

#include <cmath>
#include <string>
#include <vector>

namespace lh::synth {

// Written into Scene::generatorVersion and the data set's manifest; bumped whenever the same
// seed would give a different scene. Version 2: evaluation-shaped rooms and camera, brick,
// bands and rings, 1-3 ceiling lights, bright-panel windows, glossy and metallic furniture.
// Version 3: ceilings of any texture (35% near-white), and the photos exposed on their median
// luminance as a camera meters (synth/dataset.cpp), not on their mean.
constexpr int kGeneratorVersion = 3;

// Half-range of the reference camera's yaw about the room's depth axis, radians (35 degrees).
constexpr double kCameraYawSpread = 35.0 * M_PI / 180.0;

struct Rig {
    PinholeCamera ref;  // at the world origin with identity rotation (the world frame)
    PinholeCamera src;  // 0.05-0.15 m to the right of ref, same orientation
    PinholeCamera tgt;  // held-out view near ref
};

struct GeneratedScene {
    Scene scene;  // in the world (reference camera) frame; exposure still 1
    Rig rig;
};

// `panoramas`: file names to choose window views from. Image size of the cameras in pixels.
GeneratedScene generateScene(uint64_t seed, const std::vector<std::string>& panoramas, int width,
                             int height);

}  // namespace lh::synth
