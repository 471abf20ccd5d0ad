// Procedural indoor scenes (issue 3): a room of 3-10 m with textured walls, floor and
// ceiling, 1-3 windows showing HDR panoramas, emissive panels and lamps, 3-12 pieces of
// furniture, and a stereo rig placed inside it. Deterministic by seed.
#pragma once

#include "synth/scene.h"

#include <string>
#include <vector>

namespace lh::synth {

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
GeneratedScene generateScene(uint64_t seed, const std::vector<std::string>& panoramas,
                             int width, int height);

}  // namespace lh::synth
