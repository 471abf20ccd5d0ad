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
    int points = 8;               // random query points in free space
    int width = 240, height = 120;
    uint64_t seed = 1;
    // Timed rounds: each round renders every setting at every point once, and a row's time
    // is, per point, the fastest over the rounds, averaged over the points (the
    // reference-check row renders in the first round only). The minimum is what a method
    // costs (a busy machine only ever adds to it), and rounds spread every setting over the
    // whole run, so a drift of the machine's speed (a shared machine's changes by up to 2x within an
    // hour) falls on all settings alike and ratios stay fair.
    int repeats = 3;
    // Methods to measure ("reference-check", "ours-steps", "ours-cells", "openvdb-fixed-step",
    // "paper-spheres"); empty: all of them.
    std::vector<std::string> methods;
};

struct SpeedErrorRow {
    std::string method;    // "ours-cells", "ours-steps", "openvdb-fixed-step", "paper-spheres"
    std::string setting;   // e.g. "step 0.5, T<1e-4"
    double msPerEnvmap = 0;
    double relativeRmse = 0;  // RMSE of linear radiance / mean reference radiance
    double psnr = 0;          // dB, docs/conventions.md#metrics, mean over points
};

// Points uniformly inside level 1's box (level 0's for one-level volumes) where the medium is
// empty. A volume without empty space there (predicted volumes are dense low-alpha fog) gets
// the least dense of 64 x count random points in that box instead. Deterministic for a seed.
std::vector<Vec3d> freeSpacePoints(const RenderVolume& volume, int count, uint64_t seed);

// The `setting` of an "ours-cells" row: "2 Gauss nodes/cell, bound 1, T<0.0001" (Gauss nodes
// per lattice cell, MarchOptions::cellRefineBound, the termination threshold minTransmittance).
std::string cellQuadratureLabel(int nodes, double bound, double threshold);

std::vector<SpeedErrorRow> measureSpeedAgainstError(
    const LightingVolume& volume, const SpeedErrorOptions& options,
    const std::function<void(const std::string&)>& progress = {});

// speed_error.csv, speed_error.md (a table, then the summary of render/speed_summary.h) and
// speed_error.svg (time against error, one curve per method) in `directory`.
// `width` x `height` is the size the rows' envmaps were rendered at.
void writeSpeedErrorReport(const std::vector<SpeedErrorRow>& rows, const std::string& directory, int width,
                           int height);

// ---- Memory against error ("storing only what the scene needs") ----

struct MemoryErrorOptions {
    std::vector<double> taus{1e-4, 1e-3, 3e-3, 1e-2, 3e-2, 1e-1};  // vdb/sparsity.h bounds
    bool halfPrecision = true;   // render what a half-precision file holds
    int points = 4;              // random free-space query points (freeSpacePoints)
    int width = 240, height = 120;
    uint64_t seed = 1;
    std::string datasetDir;      // optional: a directory with cameras.json and ground-truth envmaps
    std::string scratchDir;      // where files are written to measure bytes on disk
    // Errors are measured with fine steps, so that they show what pruning changed and not
    // where the default steps happen to fall (pruning moves level boundaries, hence steps);
    // speed is timed with the default settings.
    MarchOptions errorMarch{0.1, 1e-6, true, 0.05, 0};
};

struct MemoryErrorRow {
    std::string setting;           // "unpruned" or "tau 0.001"
    double tau = 0;                // -1 for the unpruned volume
    uint64_t activeVoxels = 0;     // active density voxels, all levels
    uint64_t memoryBytes = 0;      // both grids in memory
    uint64_t diskBytesFloat = 0;   // .vdb, Blosc, 32-bit floats
    uint64_t diskBytesHalf = 0;    // .vdb, Blosc, 16-bit halves
    int levels = 0;
    double psnrVsUnpruned = 100;   // dB, mean over points (identical images capped at 100)
    double relativeRmse = 0;       // RMSE / mean radiance against the unpruned envmaps
    double msPerEnvmap = 0;        // default march settings, 2 cores
    double psnrGroundTruth = -1;   // dB, mean over the data set's envmaps (-1: no data set)
    double lossDb = 0;             // PSNR against ground truth lost by pruning, dB
};

// Sparsifies `volume` at every bound in options.taus and measures memory, bytes on disk and
// the envmap error against the unpruned volume (and against ground truth with a data set).
// The first row is the unpruned volume.
std::vector<MemoryErrorRow> measureMemoryAgainstError(
    const LightingVolume& volume, const MemoryErrorOptions& options,
    const std::function<void(const std::string&)>& progress = {});

// The storage target: at most this fraction of the dense float storage, with at most
// this many dB of envmap PSNR lost against ground truth.
constexpr double kMemoryTargetFraction = 0.1, kMemoryTargetLossDb = 0.1;

// The target read from the row at bound `tau` (the default's): on disk, in memory, and the
// loss against ground truth where the rows have it. Markdown, appended to memory_error.md.
std::string memoryTargetMarkdown(const std::vector<MemoryErrorRow>& rows, double denseBytes, double tau);

// memory_error.csv, memory_error.md and memory_error.svg (envmap error against bytes).
void writeMemoryErrorReport(const std::vector<MemoryErrorRow>& rows, const std::string& directory,
                            double denseBytes);

// PSNR (dB) a pruned volume's envmaps must reach against the unpruned ones so that a volume
// whose envmaps reach `basePsnr` against ground truth loses at most `lossDb` (triangle
// inequality on RMSE, a worst case: loss <= 20 log10(1 + rmse_prune / rmse_base)).
double requiredPsnrForLoss(double lossDb, double basePsnr);

struct BoundChoice {
    double tau = 0;         // largest bound tried that met the requirement (0: none did)
    double psnr = 100;      // its PSNR against the unpruned envmaps, dB
};
// Tries bounds from 0.1 down by factors of sqrt(10) to 1e-6 and returns the first whose
// envmaps (optionally through half precision) reach `requiredPsnr` against the unpruned ones.
BoundChoice chooseSparsityBound(const LightingVolume& volume, double requiredPsnr,
                                const MemoryErrorOptions& options,
                                const std::function<void(const std::string&)>& progress = {});

}  // namespace lh
