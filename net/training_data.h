// Reading the synthetic data sets of `lighthouse synth` (synth/dataset.h) for training and
// evaluation. The network sees what a user's camera gives: the 8-bit PNG views, decoded from
// sRGB; ground-truth envmaps are the linear HDR EXRs.
#pragma once

#include "core/camera.h"
#include "render/image.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lh::net {

struct TrainingExample {
    std::string directory;
    CamerasFile cameras;  // ref, src, tgt, near, far, envmap positions
    ImageRGB ref, src, tgt;  // linear
    std::vector<ImageRGB> envmaps;                 // linear HDR, one per cameras.envmaps entry
    std::vector<std::vector<std::uint8_t>> masks;  // observed-content masks (if requested)
};

// Example directories of a data set (those holding cameras.json), sorted by name. Throws
// FileError if `dataDir` is missing or holds none.
std::vector<std::string> listExamples(const std::string& dataDir);

// Throws FileError naming the example and the file that is missing or unreadable.
TrainingExample loadExample(const std::string& directory, bool withMasks = false);

}  // namespace lh::net
