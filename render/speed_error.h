// Speed against error of envmap renderers on one volume (issue 7): ours at several steps and
// termination thresholds, a fixed-step marcher over OpenVDB's samplers, and the paper's
// concentric spheres, all measured against our reference mode on the same random points.
#pragma once

#include "render/envmap.h"

#include <functional>
#include <string>
#include <vector>

namespace lh {

struct SpeedErrorOptions {
    int points = 8;               // random query points in free space
    int width = 240, height = 120;
    uint64_t seed = 1;
};

struct SpeedErrorRow {
    std::string method;    // "ours", "openvdb-fixed-step", "paper-spheres"
    std::string setting;   // e.g. "step 0.5, T<1e-4"
    double msPerEnvmap = 0;
    double relativeRmse = 0;  // RMSE of linear radiance / mean reference radiance
    double psnr = 0;          // dB, CONVENTIONS.md, mean over points
};

// Points uniformly inside level 1's box (level 0's for one-level volumes) where the medium is
// empty. Throws InputError if none is found.
std::vector<Vec3d> freeSpacePoints(const RenderVolume& volume, int count, uint64_t seed);

std::vector<SpeedErrorRow> measureSpeedAgainstError(
    const LightingVolume& volume, const SpeedErrorOptions& options,
    const std::function<void(const std::string&)>& progress = {});

// speed_error.csv, speed_error.md (a table) and speed_error.svg (time against error, one
// curve per method) in `directory`.
void writeSpeedErrorReport(const std::vector<SpeedErrorRow>& rows, const std::string& directory);

}  // namespace lh
