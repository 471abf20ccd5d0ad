// Prediction from a stereo pair: the public, torch-free face of the network (the CLI and the
// evaluation use it without including libtorch).
//
//   stereo pair + cameras -> depth range (cameras.json, else estimated from the pair)
//   -> plane-sweep volume -> MPI -> resampled cubes -> completed cubes -> LightingVolume.
#pragma once

#include "core/camera.h"
#include "image/image.h"
#include "net/config.h"
#include "net/depth_range.h"
#include "vdb/lighting_volume.h"
#include "vdb/mpi.h"

#include <memory>
#include <string>
#include <vector>

namespace lh::net {

struct StereoPair {
    ImageRGB ref, src;    // linear (PNG/JPEG inputs decoded from sRGB)
    CamerasFile cameras;  // ref and src required; near/far optional
};

// Throws InputError naming what is wrong: no src camera, image sizes that differ from the
// cameras, NaN or infinite pixels, a zero baseline (the pair cannot see depth), or a near/far
// pair that is not 0 < near < far.
void validateStereoPair(const StereoPair& pair);
// The method sees depth through a narrow baseline (the paper's 5-15 cm pairs); a source camera
// farther than this from the reference is most likely a wrong cameras.json (units, or a
// world-to-camera matrix given as cam_to_world). Metres.
constexpr double kImplausibleBaseline = 1.0;
// Warnings (one line each, without "warning: ") for a pair that runs but is unlike what the
// method expects: a baseline above kImplausibleBaseline, or above the near depth, or the same
// photo given as both views.
std::vector<std::string> stereoPairWarnings(const StereoPair& pair);

// A lamp the emitter head placed ("+emitters" models), as it was added to the volume.
struct PredictedEmitter {
    Vec3d position;     // metres, the volume's frame
    double radius = 0;  // metres
    double alpha = 0;   // voxel opacity at its centre
    Vec3d radiance;     // linear RGB
};

struct Prediction {
    LightingVolume volume;   // completed levels, the lighting volume
    LightingVolume mpiOnly;  // the MPI resampled onto the levels, no completion (an ablation)
    Mpi mpi;                 // in the reference camera, at the network's input size
    DepthRange range;        // used depth range; votes/fallback set when it was estimated
    bool rangeEstimated = false;
    std::vector<PredictedEmitter> emitters;  // empty unless the model has an emitter head
    double seconds = 0;                      // network time, wall clock
};

// Default pruning threshold of predicted volumes (voxel alpha): below it a voxel holds
// optical depth under 0.03 and its light barely shows, while empty-space skipping needs the
// voxels to be empty. Measured with the bundled model (docs/network.md): 0.03 keeps 24% of
// the demo pair's voxels (0.01: 34%) and scores 0.2 dB higher on dev_cycles; 0.05 loses 0.3 dB.
constexpr float kDefaultPruneAlpha = 0.03f;

// The threshold predict prunes a model of `config` at unless told otherwise: the one it was
// trained under (train --prune-alpha), else kDefaultPruneAlpha.
float defaultPruneAlpha(const NetConfig& config);

struct PredictorOptions {
    std::string model;  // empty: the bundled model (models/standard.pt)
    std::string device = "cpu";
    int threads = 0;  // 0: every core
    // Timing only: random weights of this configuration ("standard", "small" or "paper") instead of
    // a model file, so both configurations can be timed without training the paper-sized one.
    std::string untrainedConfig;
    // Voxels of the completed volume whose opacity over one voxel is below this are left
    // empty; 0 keeps everything down to volume_export.h's 1e-4. Negative: the threshold the
    // model was trained under (train --prune-alpha), else kDefaultPruneAlpha.
    float pruneAlpha = -1;
    // Collapse the completed volume into an opaque shell seen from defaultShellCentre
    // (render/radial_shell.h): the same envmap from there, far fewer voxels for rays to cross.
    bool shell = false;
    // What the completed volume holds above white, times this (net/highlight_gain.h), before
    // any shell is made; 1: as the network predicts it. Negative: the gain the model was
    // trained under (train --highlight-gain), else 1.
    double highlightGain = -1.0;
    // The gain expands only what lies above this luminance (net/highlight_gain.h): a voxel of
    // Y > knee becomes knee + gain (Y - knee). 1: everything above white.
    double highlightKnee = 1.0;
};

// The bundled model's path.
std::string defaultModelPath();

class Predictor {
public:
    explicit Predictor(const PredictorOptions& options);
    ~Predictor();
    Predictor(const Predictor&) = delete;
    Predictor& operator=(const Predictor&) = delete;

    const NetConfig& config() const;
    float pruneAlpha() const;      // the threshold in use
    double highlightGain() const;  // the gain in use
    double highlightKnee() const;  // where it starts
    Prediction predict(const StereoPair& pair) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace lh::net
