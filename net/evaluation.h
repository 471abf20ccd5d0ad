// `lighthouse eval`: the paper's Table 2 on our synthetic test split, or on any data set of
// the same layout (dev_cycles: masks computed from env_K_pos.exr, no oracle without
// scene.json). Per test envmap, four predictions are scored against the ground truth
// (docs/metrics.md: the paper's PSNR and RGB angle over all and observed content, and
// the log-luminance RMSE and diffuse-irradiance error that see HDR light), and reported as
// mean +- std:
//   ours            the completed lighting volume, rendered by the C++ ray marcher;
//   MPI only        the MPI resampled onto the levels without completion; what it leaves
//                   unseen is filled with grey (sRGB 0.5), as in the paper's ablation;
//   global envmap   one envmap per scene, used at every point (DeepLight-like): the MPI seen
//                   from the reference camera, its unobserved directions filled with the mean
//                   of the observed content (the reference image's mean colour);
//   oracle          the scene's true geometry and light voxelised into the same layout, the
//                   ceiling of any predictor at this resolution (synth/oracle.h). It needs
//                   every scene's scene.json; where one lacks it, the row is left out and
//                   the progress stream says so.
#pragma once

#include "core/shard.h"
#include "net/lamp_placement.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace lh::net {

struct EvalOptions {
    std::string data;          // test split (lighthouse synth --split test)
    std::string model;         // empty: the bundled model
    std::string out = "eval";  // directory: table.md, metrics.csv, contact_sheet.png
    int maxScenes = 0;         // 0: all
    bool oracle = true;
    std::string hdriDir;  // panoramas for the oracle's windows
    std::string device = "cpu";
    int threads = 0;
    float pruneAlpha = -1;      // predict's --prune-alpha; negative: the model's (as predict's)
    bool shell = false;         // predict's --shell
    double highlightGain = -1;  // predict's --highlight-gain; negative: the model's
    double highlightKnee = 1;   // predict's --highlight-knee
    // Also score "ours" with one part of the truth put in (image/truth_splice.h): how much a
    // perfect MPI, a perfect completion or perfect lamps and windows alone would gain.
    // Not with shards.
    bool headroom = false;
    // The model reads each example's linear renders (ref.exr, src.exr) instead of its saved
    // photos: what a user who gives an unclipped EXR photo gets (ours, and the MPI-only and
    // global rows, which come from its MPI; the global's colour stays the PNG photo's mean).
    bool unclippedPhotos = false;
    // With shard.active: only scene i with shard.owns(i), into out/metrics.shard-K-of-N.csv,
    // out/sheet.shard-K-of-N/ and out/shard-K-of-N.json; mergeEvalShards (net/eval_table.h)
    // writes table.md, metrics.csv and contact_sheet.png from a complete set.
    Shard shard;
};

struct MethodScores {
    std::string name;
    std::vector<double> psnrAll, angularAll, psnrObserved, angularObserved;
    std::vector<double> logLuminanceAll, logLuminanceObserved, irradianceError, radianceRatio;
    std::vector<double> psnrUnobserved, displayBiasUnobserved;
    std::vector<double> highlightRecall, highlightPrecision;  // NaN: no highlight to match
};

struct EvalReport {
    std::vector<MethodScores> methods;
    std::vector<MethodScores> headroom;  // with options.headroom: one per TruthPart
    // Models with an emitter head: each lamp seen from each envmap's point (lamps.csv, and a
    // line under the table; not in a shard's files).
    std::vector<LampPlacement> lamps;
    std::string markdown;  // the table
};

EvalReport evaluate(const EvalOptions& options, std::ostream& progress);

}  // namespace lh::net
