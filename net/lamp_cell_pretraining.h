// Pretraining of a "+cells" emitter head's photo classifier (net/emitter_head.h) on where the
// lamps are, from photos alone, before the fine-tuning.
//
// Fine-tuned inside the whole pipeline, the head meets each training room once, at about three
// seconds a step: 800 examples were too few for a fresh photo encoder to learn anything about
// the lamps a photo does not show (models/EXPERIMENTS.md, "the photo head"). The photo branch
// alone costs milliseconds a photo, so it can see every training photo many times first. Each
// photo is also seen mirrored left to right, with its lamps' cells mirrored (the volume's x
// axis is the photo's rightward axis).
#pragma once

#include "core/camera.h"
#include "net/emitter_head.h"
#include "net/torch_pch.h"

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace lh::net {

struct NetConfig;

// One photo and where its room's lamps and windows are.
struct LampCellExample {
    torch::Tensor photo;          // [1, 3, H, W] linear, at the network's input size
    torch::Tensor cells;          // [cells]: 1/M on the cell of each of the M lamps
    torch::Tensor mirroredCells;  // the same with the cells' x mirrored
};

// Level 0's cells (cellsPerSide^3 of them, z-major like the cubes) of a data-set example of
// far depth `far` (level 0 is the cube of side 2 min(far, 20) m centred on the camera): the
// distribution a lamp-cell loss asks for, 1/M on the cell holding each of `lamps` [M, 3]
// (metres, the reference camera's frame; those outside fall to the nearest cell), optionally
// with x mirrored. Throws InputError without lamps.
torch::Tensor lampCellTarget(const torch::Tensor& lamps, double far, int cellsPerSide,
                             bool mirrored = false);

// The centres (metres) of every emitting primitive (lamps and window panes) of a synthetic
// scene.json, [M, 3]; an undefined tensor if it has none. Throws FileError if unreadable.
torch::Tensor lampCentresOfScene(const std::string& sceneJson);

// The rows of `centres` [M, 3] (metres, the camera's frame: OpenCV axes, +z forward) that the
// photo of `camera` does not show: behind it or projecting outside its image. Only the centre
// is tested, and nothing is occluded. An undefined tensor if the photo shows them all.
torch::Tensor lampsOutsideView(const torch::Tensor& centres, const PinholeCamera& camera);

// The example of one data-set folder (ref.png, cameras.json, scene.json; ref.exr instead of
// ref.png for a configuration whose head reads the unclipped photo, where the folder has it),
// the photo resized to the configuration's input size; `ok` false when the scene has no lamps or no
// scene.json. With `unseenOnly` the cells name only the lamps and windows the photo does not show
// (lampsOutsideView), and `ok` is false where it shows them all. Throws FileError for an
// unreadable file.
LampCellExample loadLampCellExample(const std::string& directory, const NetConfig& config, bool& ok,
                                    bool unseenOnly = false);

struct LampCellScores {
    double divergence = 0;  // mean KL(cells || p), nats
    double peakHit = 0;     // share of examples whose most likely cell holds a lamp
};

// The head's photo classifier (softmax of photoCellLogits) on `examples`, without gradients.
LampCellScores scoreLampCells(EmitterHead& head, const std::vector<LampCellExample>& examples);
// The same for one distribution for every example ([cells], probabilities).
LampCellScores scoreLampCells(const torch::Tensor& distribution,
                              const std::vector<LampCellExample>& examples);

struct LampCellPretraining {
    int epochs = 30;
    int batch = 32;
    double learningRate = 1e-3;
    double weightDecay = 1e-4;  // Adam's L2 penalty
    std::uint64_t seed = 1;
};

// Trains the head's photo encoder and classifier (the rest of the head is left as it is) by
// Adam on the mean KL(cells || softmax(photoCellLogits)), the classifier's bias starting at the
// log of the training examples' own distribution (mirrored ones included; a thousandth mixed
// with uniform). Prints one line per epoch: the training divergence and, on `heldOut`, the
// divergence and peak hits against those of the training distribution. Keeps the weights of
// the epoch (0: the start) with the least held-out divergence, the last without held-out
// photos, and returns its held-out scores.
LampCellScores pretrainLampCells(EmitterHead& head, const std::vector<LampCellExample>& training,
                                 const std::vector<LampCellExample>& heldOut,
                                 const LampCellPretraining& options, std::ostream& progress);

}  // namespace lh::net
