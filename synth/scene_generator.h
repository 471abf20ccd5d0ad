// Procedural indoor scenes shaped after the evaluation rooms: 3-8 m wide (x), 4-10 m deep (z),
// 2.4-3.5 m high, with textured walls, floor and ceiling, 1-3 windows showing HDR panoramas,
// emissive panels and lamps, 3-10 pieces of furniture, and a stereo rig standing in the back
// half of the room looking down its depth. Deterministic by seed.
#pragma once

#include "core/camera.h"
#include "synth/scene.h"

#include <cmath>
#include <string>
#include <utility>
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

// Where the ceiling lights go. Random: anywhere on the ceiling, so a photo says nothing about
// where the unseen ones are. Room: as real rooms are lit, evenly spaced along the middle of the
// ceiling's longer axis (one light: its centre), each moved by at most kLampLayoutJitter, so the
// walls a photo shows say where the lights it does not show are. Only the lights' positions
// differ: the same seed gives the same room, windows, furniture and lights otherwise, and the
// same camera unless a moved lamp comes within its clearance.
enum class LampLayout { Random, Room };

// Largest shift of a light from its place in the Room layout, along each horizontal axis, m.
constexpr double kLampLayoutJitter = 0.15;

// Horizontal centres (x, z) in the room's frame (origin at the floor's centre, metres) of
// `count` lights laid out like a real room's: along the middle of the longer of the ceiling's
// axes, at (k + 1/2) / count of its length for light k.
std::vector<std::pair<double, double>> roomLampCentres(double roomWidth, double roomDepth,
                                                       int count);

struct GeneratedScene {
    Scene scene;  // in the world (reference camera) frame; exposure still 1
    Rig rig;
};

// `panoramas`: file names to choose window views from. Image size of the cameras in pixels.
GeneratedScene generateScene(uint64_t seed, const std::vector<std::string>& panoramas, int width,
                             int height, LampLayout lampLayout = LampLayout::Random);

}  // namespace lh::synth
