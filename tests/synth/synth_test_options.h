// Small, fast options for writing synthetic examples in the tests, and fresh directories.
#pragma once

#include "synth/dataset.h"

#include <filesystem>
#include <string>

namespace lh::synth::test {

inline SynthOptions smallOptions(const std::string& out) {
    SynthOptions o;
    o.out = out;
    o.width = 96;
    o.height = 72;
    o.envWidth = 96;
    o.envHeight = 48;
    o.envmapsPerExample = 1;
    o.supersample = 1;
    o.hdriDir = LIGHTHOUSE_HDRI_DIR;
    o.bake.maxTexels = 4000;
    o.bake.gatherRays = 16;
    o.bake.lightSamples = 4;
    return o;
}

inline std::filesystem::path freshDir(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("lh_synth_" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace lh::synth::test
