// Reading the synthetic data sets of `lighthouse synth` (synth/dataset.h) for training and
// evaluation, and data sets of the same layout made elsewhere (dev_cycles, rendered by
// Blender Cycles: no env_K_mask.png, no scene.json). The network sees what a user's camera
// gives: the 8-bit PNG views, decoded from sRGB; ground-truth envmaps are the linear HDR EXRs.
// Training starts from the views' EXR renders instead, where they exist, and clips them itself.
#pragma once

#include "core/camera.h"
#include "image/image.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lh::net {

struct TrainingExample {
    std::string directory;
    CamerasFile cameras;                           // ref, src, tgt, near, far, envmap positions
    ImageRGB ref, src, tgt;                        // linear
    std::vector<ImageRGB> envmaps;                 // linear HDR, one per cameras.envmaps entry
    std::vector<std::vector<std::uint8_t>> masks;  // observed-content masks (if requested)
};

// Example directories of a data set (those holding cameras.json), sorted by name. Throws
// FileError if `dataDir` is missing or holds none.
std::vector<std::string> listExamples(const std::string& dataDir);

// Throws FileError naming the example and the file that is missing or unreadable.
// With `withMasks`, envmap K's mask is env_K_mask.png when there is one; otherwise it is
// computed (net/observed_mask.h) from the envmap's position_file (env_K_pos.exr) and the
// reference view's z-depth, ref_depth.exr (dev_cycles) or depth.exr (lighthouse synth).
TrainingExample loadExample(const std::string& directory, bool withMasks = false);

// Which of an example's views have their renders read: training reads all three (the held-out
// target too); eval, like predict, only the reference and source photos the model sees.
enum class UnclippedViews { RefAndSrc, RefSrcAndTgt };

// Replaces ref, src and (for RefSrcAndTgt) tgt by the example's linear EXR renders (ref.exr,
// src.exr, tgt.exr) where it has each, of the PNGs' sizes and free of NaN; returns whether it
// did (all or none).
// Training augments exposure: a camera that exposes a scene 0.6x still clips its windows at 1,
// but a clipped PNG scaled by 0.6 shows them as flat grey at 0.6, which no camera gives, and
// which hides where the photo saturated from the network's HDR boost. Throws FileError if an
// EXR is unreadable.
bool useUnclippedViews(TrainingExample& ex, UnclippedViews views = UnclippedViews::RefSrcAndTgt);

// The first of an example folder's unclipped renders (ref.exr, src.exr and, for RefSrcAndTgt,
// tgt.exr) that it lacks, as a file name; empty when it has them all.
std::string missingUnclippedView(const std::string& directory,
                                 UnclippedViews views = UnclippedViews::RefSrcAndTgt);

}  // namespace lh::net
