// Speed against error of envmap renderers on one volume: ours at several steps and
// termination thresholds, a fixed-step marcher over OpenVDB's samplers, and the paper's
// concentric spheres, all measured against our reference mode on the same random points.
#pragma once

#include "render/envmap.h"

#include <cstdint>

#include <functional>
#include <string>
#include <vector>

namespace lh {

struct SpeedErrorOptions {
    int points = 8;  // random query points in free space
    int width = 240, height = 120;
    uint64_t seed = 1;
    // Timed rounds: each round renders every setting at every point once, and a row's time
    // is, per point, the fastest over the rounds, averaged over the points (the
    // reference-check row renders in the first round only). The minimum is what a method
    // costs (a busy machine only ever adds to it), and rounds spread every setting over the
    // whole run, so a drift of the machine's speed (a shared machine's changes by up to 2x within
    // an hour) falls on all settings alike and ratios stay fair.
    int repeats = 3;
    // Methods to measure ("reference-check", "ours-steps", "ours-cells", "openvdb-fixed-step",
    // "paper-spheres"); empty: all of them.
    std::vector<std::string> methods;
    // Step of the reference every row is measured against, in voxels of the level marched
    // (MarchOptions::reference() at the default 0.05); thick steps are sub-divided to an
    // optical depth of 0.4 x the step (0.02 at 0.05). The reference-check row renders at half
    // of both. Where bright, thin surfaces make the reference-check row's difference
    // comparable to the errors being measured, a finer reference tells them apart: each
    // halving costs about twice the time of the references (renders once, not per round).
    double referenceStep = 0.05;
    // Throws InputError for a reference step outside [0.005, 0.05] (coarser than the
    // default reference, or so fine that one envmap takes minutes).
    void validate() const;
};

// The reference's march options at `step` voxels (see SpeedErrorOptions::referenceStep).
MarchOptions referenceMarchAt(double step);

struct SpeedErrorRow {
    std::string method;   // "ours-cells", "ours-steps", "openvdb-fixed-step", "paper-spheres"
    std::string setting;  // e.g. "step 0.5, T<1e-4"
    double msPerEnvmap = 0;
    double relativeRmse = 0;  // RMSE of linear radiance / mean reference radiance
    double psnr = 0;          // dB, docs/conventions.md#metrics, mean over points
};

// The `setting` of an "ours-cells" row: "2 Gauss nodes/cell, bound 1, T<0.0001" (Gauss nodes
// per lattice cell, MarchOptions::cellRefineBound, the termination threshold minTransmittance).
std::string cellQuadratureLabel(int nodes, double bound, double threshold);

std::vector<SpeedErrorRow> measureSpeedAgainstError(
    const LightingVolume& volume, const SpeedErrorOptions& options,
    const std::function<void(const std::string&)>& progress = {});

// speed_error.csv, speed_error.md (a table, then the summary of study/speed_summary.h) and
// speed_error.svg (time against error, one curve per method) in `directory`.
// `width` x `height` is the size the rows' envmaps were rendered at.
void writeSpeedErrorReport(const std::vector<SpeedErrorRow>& rows, const std::string& directory,
                           int width, int height);

}  // namespace lh
