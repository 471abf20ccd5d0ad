// Training losses (docs/method.md#losses).
//  - imageLoss: L1 on sRGB-encoded clamp(linear, 0, 1) (the space the PSNR metric uses) plus
//    L1 on image gradients at two scales. This is our documented substitute for the VGG-19
//    perceptual loss, whose weights we cannot download here.
//  - PatchGAN discriminator: 4x4 convolutions 64-128-256-512-1, leaky ReLU 0.2, spectral
//    normalisation on every convolution; hinge loss.
#pragma once

#include "net/torch_pch.h"

namespace lh::net {

torch::Tensor imageLoss(const torch::Tensor& predictedLinear, const torch::Tensor& targetLinear);

// Squared-error image loss: the mean squared difference of sRGB-encoded clamp(linear, 0, 1),
// exactly the quantity PSNR = -10 log10(loss) scores. Where the network cannot tell what an
// unseen wall holds, imageLoss's L1 pulls towards the median of the possibilities; this loss
// pulls towards their mean, which is what PSNR rewards.
torch::Tensor squaredImageLoss(const torch::Tensor& predictedLinear,
                               const torch::Tensor& targetLinear);

// HDR image loss: mean |ln(1 + pred) - ln(1 + target)| over pixels and channels, on linear
// radiance. Unlike imageLoss it sees how bright a lamp or window is (imageLoss clamps at 1).
torch::Tensor hdrImageLoss(const torch::Tensor& predictedLinear, const torch::Tensor& targetLinear);

// Coarse HDR image loss: hdrImageLoss of the two images averaged, in linear radiance, over
// blocks of `block` x `block` pixels (a trailing part block is left out). At full resolution a
// lamp smaller than a voxel, which the volume can only show spread over the wall around it, is
// charged on every wall pixel it brightens, and the per-pixel losses keep it dim; averaged over
// a block as large as that spread, a lamp of the right power in the right block costs nothing,
// however it is spread inside the block. `block` 1 is hdrImageLoss; a block larger than the
// image is cut to the image's shorter side.
torch::Tensor coarseHdrImageLoss(const torch::Tensor& predictedLinear,
                                 const torch::Tensor& targetLinear, int block);

// What the PatchGAN discriminator sees of an HDR envmap under `train --adversarial-input log`:
// ln(1 + radiance) / ln(1 + 100), so 0 is black, 1 a radiance of 100 and a lamp of 1000 is 1.5.
// sRGB (srgbEncodeTensor) clamps at 1, where a white wall and a lamp look alike; this keeps
// their difference, so the discriminator can ask for lamps as bright as real ones.
constexpr double kAdversarialLogPeak = 100.0;
torch::Tensor logRadianceEncode(const torch::Tensor& linear);

// Highlight loss: asks an envmap to show the lamps and windows that a mirror ball would show
// and the photo saw (image/highlights.h: luminance Y above kLampLuminance = 1), and no others.
// Envmaps [N, 3, H, W] linear; `observed` [N, 1, H, W], nonzero where the reference photo sees
// the pixel's first surface. The mean over all pixels of
//   at observed true highlights: relu(ln(1 + min(Y_gt, 2)) - ln(1 + Y_pred)),
//   at pixels whose truth is not a highlight: relu(ln(1 + Y_pred) - ln 2),
//   elsewhere (true highlights the photo did not see): 0.
// Each pixel pays for its own term, so a lamp pixel left dim and a wall pixel shown as a
// highlight cost alike. (Taking each term's mean over its own pixels instead made a false
// highlight cost about a hundredth of a missed lamp pixel: the model then showed more lamps
// and as many false ones; models/EXPERIMENTS.md, "the highlight loss".)
torch::Tensor highlightLoss(const torch::Tensor& predictedLinear, const torch::Tensor& targetLinear,
                            const torch::Tensor& observed);

// Diffuse-irradiance loss: the cosine-weighted integrals of linear radiance over the six axis
// normals (the irradiance a diffuse surface facing +-x, +-y, +-z receives, as the metric of
// docs/metrics.md), their mean relative error |E_pred - E_gt| / E_gt (E_gt floored at 1e-3 of
// its mean). Envmaps [N, 3, H, W] in the equirectangular layout. A lamp the photo cannot place
// costs the per-pixel losses twice where it is guessed wrong, and so they leave it out; this
// loss asks only for the right light from each side, which a compact bright guess gives.
torch::Tensor irradianceLoss(const torch::Tensor& predictedLinear,
                             const torch::Tensor& targetLinear);

// irradianceLoss with the same value, its gradient focused on the prediction's brightest
// pixels: each pixel's share of the gradient is (Y / mean Y)^focus, Y the predicted luminance
// (detached; shares normalised to a mean of 1 per envmap). The plain loss asks every pixel for
// light alike, and the per-pixel losses then pay for a room brightened all over; at focus 1
// it asks each pixel for the same relative gain, so the light goes where the prediction
// already holds lamps and windows. focus 0 is irradianceLoss.
torch::Tensor focusedIrradianceLoss(const torch::Tensor& predictedLinear,
                                    const torch::Tensor& targetLinear, double focus);

// The six axis irradiances [N, 3, 6] of envmaps [N, 3, H, W] (normals +x, -x, +y, -y, +z, -z).
torch::Tensor axisIrradianceTensor(const torch::Tensor& envmaps);

// Direct supervision of the cubes by the oracle's (net/oracle_targets.h), both [1, 4, R, R, R]
// per level (rgb, voxel alpha): per level, for alpha, the L1 (whose optimum under uncertainty
// is empty or opaque, not fog) plus a tenth of the binary cross-entropy (alpha clamped to
// [1e-4, 1 - 1e-4]; it keeps a gradient through a saturated sigmoid), and for colour,
// alpha_oracle times the L1 of ln(1 + rgb) (colour where the oracle has matter); each voxel
// weighted by 1 + 2 alpha_oracle; the mean over levels.
torch::Tensor voxelLoss(const std::vector<torch::Tensor>& predicted,
                        const std::vector<torch::Tensor>& target);

// The MPI's depth against the reference view's true depth: the L1 of the composited
// disparity (the remaining transmittance lands on the far plane) against 1 / depth, divided by
// the planes' disparity range so that it is 1 for a prediction off by the whole range.
// mpi [1, 4, D, H, W], planes far to near at `depths`; trueDepth [1, 1, H, W], metres.
torch::Tensor mpiDepthLoss(const torch::Tensor& mpi, const std::vector<double>& depths,
                           const torch::Tensor& trueDepth);

// The MPI's expected disparity per pixel [1, 1, H, W] (used by mpiDepthLoss and its tests).
torch::Tensor mpiExpectedDisparity(const torch::Tensor& mpi, const std::vector<double>& depths);

// A sparsity prior for training without 3D ground truth: the mean voxel alpha of every cube.
torch::Tensor sparsityLoss(const std::vector<torch::Tensor>& cubes);

// A prior towards empty or opaque voxels: the mean over the cubes of alpha (1 - alpha), 0 where
// every voxel is empty or opaque, 0.25 at most. Fog is what empty-space skipping and early ray
// termination cannot use; this asks each voxel to decide.
torch::Tensor binaryAlphaLoss(const std::vector<torch::Tensor>& cubes);

// Direct supervision of the emitter head's lamps (net/emitter_head.h): the mean over its lamps
// [K, 3] of the squared distance (m^2) to the nearest of the scene's true lamps and windows
// [M, 3] (their centres). 0 when every lamp sits on a true one.
torch::Tensor emitterPositionLoss(const torch::Tensor& lamps, const torch::Tensor& trueLamps);

// The Kullback-Leibler divergence KL(t || p) (nats) of each row: targets t [N, cells]
// (probabilities) and log p [N, cells]. [N]. Cells of target 0 add nothing, even where
// log p = -inf.
torch::Tensor cellDivergence(const torch::Tensor& target, const torch::Tensor& logProbability);

// Supervision of where the emitter head puts light, as a classification over level 0's cells
// (net/emitter_head.h): KL(t || p) from the true distribution t [cells] (1/M on the cell of each
// of the scene's M true lamps and windows: net/lamp_cell_pretraining.h lampCellTarget) to the
// head's, p = the mean over its K lamps of softmax(cellLogits [K, cells]). 0 when p = t;
// unlike a squared distance, an uncertain head lowers it by spreading p over the likely
// cells, not by moving to their mean.
torch::Tensor emitterCellLoss(const torch::Tensor& cellLogits, const torch::Tensor& target);

// A prior for closed rooms: the mean over an envmap's rays of the transmittance left behind
// the volume ([1, 1, H, W], TorchEnvmap::transmittance); 0 where every ray ends on something
// opaque, 1 for an empty volume. The training rooms are closed, so every ray from inside
// ends on a wall. A fog lets rays leave the volume instead: they miss the light they should
// have gathered, and the envmap renderer marches them through every level (`bench-envmap`'s
// ray budget measures it: rays that never stop cost the most).
torch::Tensor closureLoss(const torch::Tensor& transmittance);

// A 4x4 convolution whose weight is divided by its largest singular value, estimated by one
// power iteration per training forward pass (Miyato et al. 2018).
struct SpectralConv2dImpl : torch::nn::Module {
    SpectralConv2dImpl(int in, int out, int stride);
    torch::Tensor forward(const torch::Tensor& x);
    torch::Tensor weight, bias, u;  // u: the power iteration's left singular vector (a buffer)
    int stride;
};
TORCH_MODULE(SpectralConv2d);

struct PatchDiscriminatorImpl : torch::nn::Module {
    PatchDiscriminatorImpl();
    // [N, 3, H, W] sRGB-encoded images in [0, 1] -> patch scores [N, 1, h, w].
    torch::Tensor forward(const torch::Tensor& x);
    std::vector<SpectralConv2d> layers;
};
TORCH_MODULE(PatchDiscriminator);

// Hinge losses: the discriminator's on real and fake scores, and the generator's.
torch::Tensor discriminatorHingeLoss(const torch::Tensor& realScores,
                                     const torch::Tensor& fakeScores);
torch::Tensor generatorHingeLoss(const torch::Tensor& fakeScores);

// Sets non-finite gradient entries to zero (the paper's NaN guard) and returns how many were.
int64_t zeroNonFiniteGradients(const std::vector<torch::Tensor>& parameters);

}  // namespace lh::net
