// Sizes of the prediction pipeline. Two named configurations share every line of code:
// `paper` (the paper's sizes) and `small` (sizes that train on 2 CPU cores in about an hour).
// Torch-free: the CLI and tests read it without libtorch.
#pragma once

#include <string>

namespace lh::net {

struct NetConfig {
    std::string name = "small";
    int width = 128;   // network input width, pixels (multiple of 16: four stride-2 stages)
    int height = 96;   // network input height, pixels (multiple of 16)
    int planes = 16;   // MPI / plane-sweep planes D (multiple of 16)
    int levels = 5;    // nested cubes L
    int resolution = 32;  // voxels per cube side R (multiple of 16)
    int baseWidth = 8;    // channels of the first encoder stage (the paper's 8)
    // Training renderer: envmap size and samples per level along each ray.
    int trainEnvWidth = 60;
    int trainEnvHeight = 30;
    int samplesPerLevel = 64;

    static NetConfig small();
    static NetConfig paper();
    // "small" or "paper"; throws InputError otherwise.
    static NetConfig byName(const std::string& name);

    // Throws InputError naming the bad size.
    void validate() const;
    std::string toJson() const;
    static NetConfig fromJson(const std::string& text, const std::string& sourceName);
};

}  // namespace lh::net
