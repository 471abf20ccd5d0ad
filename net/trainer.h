// `lighthouse train`. Two kinds of supervision:
//   direct (the default): every loss from the first iteration, for every network at once:
//     the held-out view (image loss), the MPI's depth against the reference depth map, the
//     cubes against the example's oracle volume (voxel loss on alpha and premultiplied
//     radiance), and the rendered envmap against the HDR ground truth (image loss on clamped
//     sRGB plus the log-radiance L1). The synthetic scenes' exact depth and oracle make this
//     converge in CPU-hours; an example without depth.exr or oracle.vdb skips that term.
//   paper: the paper's staged schedule without 3D ground truth:
//     stage 1 (first 25% of iterations): the MPI network alone, on the held-out view;
//     stage 2 (to 90%): the envmap losses added (and a small sparsity prior on the cubes);
//     stage 3 (last 10%): the PatchGAN adversarial loss added (weight 0.1).
// Image losses: the paper's VGG-19 perceptual loss with --vgg FILE, else the substitute of
// losses.h. Adam at --lr, divided by 10 for the last 20% (the paper's 1e-4 -> 1e-5); batch 1 (or
// --batch); non-finite gradients zeroed; gradients clipped to a global norm of 5; the model written
// is the moving average of the weights (--average-decay). Each iteration draws its example and
// augmentation (net/augment.h) from (seed, iteration) alone, so a resumed run repeats exactly what
// an uninterrupted one would have done.
#pragma once

#include "net/config.h"
#include "net/distributed.h"

#include <iosfwd>
#include <optional>
#include <string>

namespace lh::net {

struct TrainOptions {
    std::string data;        // training split (lighthouse synth --split train)
    std::string validation;  // held-out scenes; empty: the last 5% of `data`, not trained on
    // Leave out scenes of `data` with an envmap clipped (channel mean above 1) on more than this
    // fraction of its pixels, before the held-out split (net/exposure_filter.h); 1: keep all.
    double maxClipped = 1.0;
    // Lower each example's exposure until at most this fraction of its reference photo's pixels
    // clip, as a camera metering for its highlights does (needs the views' unclipped EXRs); 1:
    // the exposure as drawn.
    double maxPhotoClipped = 1.0;
    std::string config = "standard";
    std::string out = "model.pt";  // model; the log is OUT.csv/.png
    std::string checkpoint;        // resumable state; empty: OUT.checkpoint
    std::string init;  // model to fine-tune from (fresh optimiser) when no checkpoint exists
    // With a model of another configuration as `init`: start from its parameters wherever name
    // and shape match (a `standard` model's MPI network for `wide`), the rest fresh.
    bool initPartial = false;
    // With a model of half the completion width as `init` (standard into wide): start from the
    // same function, each completion channel split in two (net/widen.h).
    bool initWiden = false;
    std::string supervision = "direct";  // "direct" or "paper" (see above)
    bool augment = true;
    bool halfModel = true;  // OUT in half precision (the checkpoint keeps float32)
    int stopAfter =
        0;  // end this sitting after this many iterations (checkpointed); 0: run to the end
    std::optional<NetConfig> configOverride;  // sizes other than the named configurations (tests)
    int iterations = 12000;
    double learningRate = 3e-4;
    int validateEvery = 500;
    int validationScenes = 8;
    int checkpointEvery = 250;
    int logEvery = 25;
    unsigned long long seed = 1;
    std::string device = "cpu";
    int threads = 0;
    bool resume = true;      // continue from OUT.checkpoint when it exists
    std::string vggWeights;  // VGG-19 weights (net/vgg_loss.h): the paper's perceptual loss
                             // instead of the substitute
    // Examples per iteration, over all ranks; each loss is divided by it, so the gradient is
    // the batch's mean. Example j of iteration i draws from (seed, i, j), example 0 from
    // (seed, i) alone, as with batch 1.
    int batch = 1;
    // The model written and validated is the exponential moving average of the weights with
    // this decay per iteration (net/weight_average.h); 0: the weights of the last step.
    double averageDecay = 0.998;
    // Weight of the diffuse-irradiance loss (net/losses.h) beside the per-pixel envmap losses.
    // Its relative error is 0.3-1 where a model misses the lamps, about the size of the
    // per-pixel losses; 0.5 keeps those in charge of where things are.
    double irradianceWeight = 0.5;
    // Where the irradiance loss's gradient goes (net/losses.h focusedIrradianceLoss): 0 to
    // every pixel alike, 1 to each pixel in proportion to its predicted luminance (a relative
    // gain), so that the light it asks for lands on the lamps and windows the model predicts.
    double irradianceFocus = 0.0;
    // Weight of the squared sRGB error of envmaps (net/losses.h squaredImageLoss, the PSNR's
    // own quantity) beside the L1 losses; 0: off. Its values are ~0.03 where L1's are ~0.15,
    // so a weight of a few units is needed to move the L1's median towards the mean.
    double envmapSquaredWeight = 0.0;
    // Weight of the highlight loss (net/losses.h highlightLoss) on the envmaps: the lamps and
    // windows the photo saw at least min(Y, 2) bright, nothing else above 1, as a mirror ball
    // shows them. Needs the examples' observed masks (net/training_data.h loadExample). 0: off.
    double highlightWeight = 0.0;
    // Weight of the coarse HDR envmap loss (net/losses.h coarseHdrImageLoss): the light of each
    // block of the envmap, however it is spread inside the block, so that a lamp shown as bright
    // as it is but spread over a voxel is not charged for the wall around it. 0: off.
    double coarseEnvmapWeight = 0.0;
    // Side of its blocks, envmap pixels (4: 12 degrees of a 120x60 training envmap). Larger
    // blocks also forgive a lamp placed a little off.
    int coarseEnvmapBlock = 4;
    // Weight of the HDR view loss (net/losses.h hdrImageLoss: L1 of ln(1 + radiance)) of the
    // MPI's rendering of the held-out view against that view's unclipped render (tgt.exr,
    // where the example has it). The clamped image loss cannot see a window brighter than 1;
    // this term is what tells the MPI how far to boost the pixels where the photo saturated.
    // 0: off.
    double viewHdrWeight = 0.0;
    // Train under pruning: the envmaps of the losses and of validation are rendered from the
    // cubes with every voxel of alpha below this left empty, as predict will leave them, with
    // straight-through gradients (net/volume_render.h). The model records it, and predict
    // prunes there by default. A model that keeps its light through a high threshold has
    // opaque walls and empty rooms, which the envmap renderer skips. 0: off.
    double pruneAlpha = 0.0;
    // Train under a highlight gain (net/highlight_gain.h): every loss on the completed cubes
    // sees them with what each voxel holds above white multiplied by this, as predict will
    // export them. The model records it, and predict applies it by default. Starting from a
    // model trained without it, the lamps it shows are at once as bright as the gain makes
    // them, and training can then put out the false ones. 1: off.
    double highlightGain = 1.0;
    // Weight of the prior towards empty or opaque voxels (net/losses.h binaryAlphaLoss) on the
    // cubes; with pruneAlpha, what asks for the empty rooms and opaque walls the renderer
    // skips and stops at. 0: off.
    double alphaBinaryWeight = 0.0;
    // Weight of the lamp-position loss (net/losses.h emitterPositionLoss) on the emitter head's
    // lamps (+emitters models): the squared distance from each to the nearest lamp or window of
    // the example's scene.json. Direct supervision of where lamps are, which the render losses
    // alone did not teach. 0: off.
    double emitterPositionWeight = 0.0;
    // Weight of the lamp-cell loss (net/losses.h emitterCellLoss) on the emitter head's
    // distribution over level 0's cells: the divergence from the cells of the example's true
    // lamps and windows (scene.json). Where the position loss teaches the mean of where lamps
    // may be, this keeps the likely places apart. 0: off.
    double emitterCellWeight = 0.0;
    // The lamp cells (the cell loss's and the pretraining's targets) name only the lamps and
    // windows the reference photo does not show (net/lamp_cell_pretraining.h lampsOutsideView):
    // those the photo shows are in the MPI already, and a classifier trained on all of them
    // peaks on the visible ones. Examples whose photo shows them all get no cell target.
    bool lampCellsUnseenOnly = false;
    // Weight of the emitter light loss (net/emitter_light.h emitterLightLoss) on the emitter
    // head's lamps: their axis irradiance per colour at each training envmap's point, as small
    // sources pruned as predict prunes, against that of the envmap's unobserved highlights
    // (luminance above 1): on a log scale short of it, linearly beyond. It asks the lamps for
    // the truth's power, through their radiance and opacity, where the envmap losses only say
    // "not like that". 0: off.
    double emitterLightWeight = 0.0;
    // Epochs of pretraining of a "+cells" emitter head's photo classifier on the photos alone
    // (net/lamp_cell_pretraining.h) of every scene that is not held out (--max-clipped does not
    // apply), before the first step of a fresh run; the log scores it on the held-out scenes
    // against the training photos' own distribution of lamp cells. 0: none.
    int pretrainLampCellEpochs = 0;
    // Weight of the closed-room prior (net/losses.h closureLoss): the transmittance each
    // envmap ray has left behind the (pruned) volume. The training rooms are closed; fog lets
    // rays leave through the walls, dark and slow to render. 0: off.
    double closureWeight = 0.0;
    // Weight of the paper's PatchGAN loss under direct supervision, from the first step (the
    // paper's own supervision adds it at 0.1 in its last stage). The per-pixel losses ask for
    // the mean of what the unseen part of a room may hold, a lampless blur; the discriminator
    // asks for envmaps that look like rooms, lamps and windows included. 0: off.
    double directAdversarialWeight = 0.0;
    // What the discriminator sees of an envmap: "srgb" (the paper's: sRGB, clamped at 1) or
    // "log" (net/losses.h logRadianceEncode: ln(1 + radiance), which tells a lamp from a
    // white wall).
    std::string adversarialInput = "srgb";
    // World size > 1: data-parallel training (net/distributed.h). Rank R trains examples
    // [R, R + 1) * batch / worldSize of every global batch; gradients are summed over ranks
    // before each step; rank 0 alone writes the model, checkpoint, log and plot; every rank
    // resumes from the same checkpoint (a shared file system).
    DistributedOptions distributed;

    void validate() const;  // throws InputError
    std::string checkpointPath() const {
        return checkpoint.empty() ? out + ".checkpoint" : checkpoint;
    }
};

// Runs training, writing progress lines to `progress`.
void train(const TrainOptions& options, std::ostream& progress);

}  // namespace lh::net
