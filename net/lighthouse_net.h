// The whole prediction model: the MPI network and one completion network per level, and the
// differentiable pipeline that runs them (docs/method.md).
#pragma once

#include "core/camera.h"
#include "image/image.h"
#include "net/config.h"
#include "net/emitter_head.h"
#include "net/torch_pch.h"
#include "net/unet2d.h"
#include "net/unet3d.h"
#include "vdb/volume_layout.h"

#include <vector>

namespace lh::net {

// The largest radiance a photo pixel is read as: the largest half float, what an EXR's half
// channels hold (an infinite pixel reads as this).
constexpr double kMaxPhotoRadiance = 65504.0;

// What the pipeline needs for one stereo pair, already at the network's input size.
struct PairInputs {
    torch::Tensor refEncoded, srcEncoded;  // [1, 3, H, W] sRGB-encoded, in [0, 1]
    torch::Tensor refLinear;               // [1, 3, H, W] linear, clipped at 1 as a photo is
    // [1, 3, H, W] linear, before the clip: above 1 where an EXR photo (or, in training, an
    // example's unclipped render) keeps its lamps' and windows' radiance. Read only by a photo
    // head that reads the unclipped photo (NetConfig::emitterPhotoUnclipped).
    torch::Tensor refUnclipped;
    PinholeCamera ref, src;      // intrinsics of the resized images
    std::vector<double> depths;  // plane depths, far to near
    VolumeLayout layout;
};

struct PipelineOutput {
    torch::Tensor mpi;                    // [1, 4, D, H, W]: linear RGB, alpha
    std::vector<torch::Tensor> mpiCubes;  // resampled MPI per level, [1, 4, R, R, R]
    std::vector<torch::Tensor> cubes;     // completed levels (empty if not run)
    Emitters emitters;                    // undefined tensors without an emitter head
};

struct LighthouseNetImpl : torch::nn::Module {
    explicit LighthouseNetImpl(const NetConfig& config);
    NetConfig config;
    UNet3d mpiNet{nullptr};            // config.mpiNetwork == "3d"
    UNet2d mpiNet2d{nullptr};          // config.mpiNetwork == "2d"
    std::vector<UNet3d> completion;    // coarsest first
    EmitterHead emitterHead{nullptr};  // config.emitters > 0

    // The MPI from the plane-sweep volume [1, 6, D, H, W] and the linear reference image:
    // per plane, alpha and a weight that blends the reference image (brightened where it
    // clipped, HDR configurations only) with a predicted background colour.
    // `logAnchor` ([1, 3, 1, 1, 1] or undefined): see logColourAnchor.
    torch::Tensor predictMpi(const torch::Tensor& psv, const torch::Tensor& refLinear,
                             const torch::Tensor& logAnchor = {});
    // Completed levels, coarse to fine, each blended with its input cube by a predicted weight.
    // The networks run at config.completionResolution(); below the cube resolution their
    // outputs (colour, alpha, weight logits) are upsampled trilinearly before the blend.
    // Besides the cubes, every network sees where its voxels are: their centres in the
    // reference camera's frame in units of 4 m (so the floor below the camera, or the wall
    // behind it, is at the same value on every level), for the `standard` design.
    std::vector<torch::Tensor> complete(const std::vector<torch::Tensor>& inputCubes,
                                        const VolumeLayout& layout,
                                        const torch::Tensor& logAnchor = {});
    // ln of the photo's mean linear colour per channel, [1, 3, 1, 1, 1] (floored at 1e-3), added
    // to every invented colour's logit when config.colourAnchor; undefined otherwise.
    torch::Tensor logColourAnchor(const torch::Tensor& refLinear) const;
    // The MPI, its cubes and, with runCompletion, the completed cubes (with the emitters added
    // when the configuration has them).
    PipelineOutput run(const PairInputs& inputs, bool runCompletion = true);
};
TORCH_MODULE(LighthouseNet);

// A linear photo at the network's input size [1, 3, height, width], its radiance as the
// pipeline reads it: NaN and negative values as 0, infinity as kMaxPhotoRadiance, nothing
// clipped.
torch::Tensor photoRadianceTensor(const ImageRGB& photo, int width, int height);

// Network inputs for a pair of linear images at any size: resized to the configuration's input
// size (intrinsics scaled), planes linear in disparity between near and far, and the layout
// of the volume (docs/conventions.md#nested-volume-layout: s0 = 2 min(far, 20)).
PairInputs makePairInputs(const ImageRGB& ref, const ImageRGB& src, const PinholeCamera& refCamera,
                          const PinholeCamera& srcCamera, double near, double far,
                          const NetConfig& config, const torch::Device& device);

// The part of completed level k-1 that level k covers, upsampled 2x (nearest): [1, C, R, R, R].
torch::Tensor cropCoarserLevel(const torch::Tensor& coarser, int coarserLevel);

// Copies every parameter and buffer of `from` into `to` (same configuration), without autograd.
void copyWeights(LighthouseNet& to, LighthouseNet& from);

// Copies each parameter and buffer of `from` into `to` where both have one of that name and
// shape (a `standard` model's MPI network into a `wide` one), and leaves the rest as they are.
// A tensor of `to` that only has more input channels (dimension 1: the completion stems of a
// "+profile" configuration) takes `from`'s weights for the old channels and zero for the new,
// so the model predicts what `from` did.
struct MatchedWeights {
    int copied = 0, tensors = 0;           // tensors of `to`
    int extended = 0;                      // of the copied: with input channels added (zero)
    int64_t copiedValues = 0, values = 0;  // their values
};
MatchedWeights copyMatchingWeights(LighthouseNet& to, LighthouseNet& from);

// Model files: the configuration and every parameter, written atomically; in half precision
// with `halfPrecision` (half the size; outputs within about 1e-3 relative), read back as float.
void saveModel(LighthouseNet& net, const std::string& path, bool halfPrecision = false);
LighthouseNet loadModel(const std::string& path, const torch::Device& device);

}  // namespace lh::net
