// The sparsity bound `lighthouse sparsify` picks when not given --tau: the loosest bound
// (vdb/sparsity.h) whose envmaps, at random free-space points and through the file's
// precision, stay within a PSNR of the unpruned ones that guarantees at most a given loss
// against ground truth.
#pragma once

#include "render/ray_marcher.h"
#include "vdb/lighting_volume.h"

#include <cstdint>
#include <functional>
#include <string>

namespace lh {

// PSNR (dB) a pruned volume's envmaps must reach against the unpruned ones so that a volume
// whose envmaps reach `basePsnr` against ground truth loses at most `lossDb` (triangle
// inequality on RMSE, a worst case: loss <= 20 log10(1 + rmse_prune / rmse_base)).
// Throws InputError unless lossDb > 0 and both are finite.
double requiredPsnrForLoss(double lossDb, double basePsnr);

struct BoundSearchOptions {
    int points = 4;  // random free-space query points (render/free_space.h)
    int width = 240, height = 120;
    uint64_t seed = 1;
    bool halfPrecision = true;  // render what a half-precision file holds
    int mantissaBits = 0;       // render what a file rounded to these bits holds (0: unrounded)
    std::string scratchDir;     // where trial files go (empty: a fresh temporary directory)
    // Errors are measured with fine steps, so that they show what pruning changed and not
    // where the default steps happen to fall (pruning moves level boundaries, hence steps).
    MarchOptions errorMarch{0.1, 1e-6, true, 0.05, 0};
};

struct BoundChoice {
    double tau = 0;     // largest bound tried that met the requirement (0: none did)
    double psnr = 100;  // its PSNR against the unpruned envmaps, dB
};
// Tries bounds from 0.1 down by factors of sqrt(10) to 1e-6 and returns the first whose
// envmaps (optionally through the file's half precision or mantissa rounding) reach
// `requiredPsnr` against the unpruned ones.
BoundChoice chooseSparsityBound(const LightingVolume& volume, double requiredPsnr,
                                const BoundSearchOptions& options,
                                const std::function<void(const std::string&)>& progress = {});

}  // namespace lh
