// Where a training step's time goes, stage by stage, for a configuration at its own sizes
// (bench/train_step_bench.cpp prints it). Torch-free, so benchmarks build without libtorch's
// headers. Each stage is timed on its own graph, forward then backward, with inputs of the
// real shapes (a textured plane seen by a stereo pair), so the sum approximates one step.
#pragma once

#include "net/config.h"

#include <string>
#include <vector>

namespace lh::net {

struct StageTime {
    std::string stage;
    double forwardSeconds = 0;   // mean over repeats, wall clock
    double backwardSeconds = 0;  // 0 for stages without parameters or gradients
};

// `threads` libtorch threads; oneDnn: whether convolutions take oneDNN's kernels (fast_conv.h).
std::vector<StageTime> profileTrainingStep(const NetConfig& config, int repeats, int threads,
                                           bool oneDnn);

}  // namespace lh::net
