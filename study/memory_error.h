// Memory against error of a lighting volume ("storing only what the scene needs"): the
// volume sparsified at several bounds (vdb/sparsity.h), each measured in memory, on disk (float,
// half, and optionally floats rounded to fewer mantissa bits) and by its envmaps against the
// unpruned volume's, and against ground truth with a data set; the storage target and the
// report of `lighthouse bench-sparsity`.
#pragma once

#include "render/ray_marcher.h"
#include "vdb/lighting_volume.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace lh {

struct MemoryErrorOptions {
    std::vector<double> taus{1e-4, 1e-3, 3e-3, 1e-2, 3e-2, 1e-1};  // vdb/sparsity.h bounds
    bool halfPrecision = true;  // render what a half-precision file holds
    // Not 0: each setting is also stored as floats rounded to this many mantissa bits
    // (vdb/mantissa_rounding.h), and the pruned rows render that file instead.
    int mantissaBits = 0;
    int points = 4;  // random free-space query points (render/free_space.h)
    int width = 240, height = 120;
    uint64_t seed = 1;
    std::string datasetDir;  // optional: a directory with cameras.json and ground-truth envmaps
    std::string
        scratchDir;  // where files are written to measure bytes on disk (empty: a temporary one)
    // Errors are measured with fine steps, so that they show what pruning changed and not
    // where the default steps happen to fall (pruning moves level boundaries, hence steps);
    // speed is timed with the default settings.
    MarchOptions errorMarch{0.1, 1e-6, true, 0.05, 0};
};

struct MemoryErrorRow {
    std::string setting;            // "unpruned" or "tau 0.001"
    double tau = 0;                 // -1 for the unpruned volume
    uint64_t activeVoxels = 0;      // active density voxels, all levels
    uint64_t memoryBytes = 0;       // both grids in memory
    uint64_t diskBytesFloat = 0;    // .vdb, Blosc, 32-bit floats
    uint64_t diskBytesHalf = 0;     // .vdb, Blosc, 16-bit halves
    int mantissaBits = 0;           // the rounding of diskBytesRounded (0: not measured)
    uint64_t diskBytesRounded = 0;  // .vdb, Blosc, floats rounded to mantissaBits
    int levels = 0;
    double psnrVsUnpruned = 100;  // dB, mean over points (identical images capped at 100)
    double relativeRmse = 0;      // RMSE / mean radiance against the unpruned envmaps
    double msPerEnvmap = 0;       // default march settings, 2 cores
    double psnrGroundTruth = -1;  // dB, mean over the data set's envmaps (-1: no data set)
    double lossDb = 0;            // PSNR against ground truth lost by pruning, dB
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

// The target read from the row at bound `tau` (the default's): on disk (the rounded file where
// the rows have one, else the half one), in memory, and the loss against ground truth where
// the rows have it. Markdown, appended to memory_error.md.
std::string memoryTargetMarkdown(const std::vector<MemoryErrorRow>& rows, double denseBytes,
                                 double tau);

// memory_error.csv, memory_error.md and memory_error.svg (envmap error against bytes).
void writeMemoryErrorReport(const std::vector<MemoryErrorRow>& rows, const std::string& directory,
                            double denseBytes);

}  // namespace lh
