#include "net/emitter_head.h"

#include "net/hdr.h"
#include "net/mpi_resample.h"
#include "net/tensor_image.h"

#include <limits>

namespace lh::net {

namespace F = torch::nn::functional;

namespace {

// The head reads level 0 at 32^3: radiance feature (3), alpha (1), voxel position (3).
constexpr int kInputChannels = 7;
constexpr int64_t kReadResolution = 32;
constexpr double kPositionUnit = 4.0;  // metres, as the completion networks see positions
// A new head starts dim (opacity sigmoid(-4) = 0.018), so that a model fine-tuned with one
// begins by predicting what it predicted without, and lamp-bright: e^3 = 20 times the photo's
// mean luminance.
constexpr double kStartOpacityLogit = -4.0;
constexpr double kStartLogBrightness = 3.0;
// The photo encoder of a "+photo" head: channels per stage, and the grid of places it keeps
// (rows x columns) before mixing them into one feature vector.
constexpr int64_t kPhotoChannels = 32;
constexpr int64_t kPhotoRows = 3, kPhotoColumns = 4;
// Dropout in the "+cells" classifier: a few thousand training photos, each seen many times in
// pretraining, are memorised without it (the held-out divergence rose after 10 epochs).
constexpr double kPhotoCellsDropout = 0.3;

// Voxel centres of `level` as [R, R, R, 3] (z, y, x order of the cubes), on `like`'s device.
torch::Tensor centresLike(const VolumeLayout& layout, int level, const torch::Tensor& like) {
    return voxelCentres(layout, level).to(like.device(), torch::kFloat32);
}

}  // namespace

EmitterHeadImpl::EmitterHeadImpl(int k, bool photo, bool classifies, bool apart)
    : count(k), readsPhoto(photo), classifiesPhoto(classifies), placesApart(apart) {
    TORCH_CHECK(readsPhoto || !classifiesPhoto, "a photo classifier needs the photo encoder");
    TORCH_CHECK(readsPhoto || !placesApart, "lamps placed apart need the photo head's peaks");
    down1 = register_module("down1", PreActConv(kInputChannels, 16, 2));
    if (readsPhoto) {
        namespace nn = torch::nn;
        const auto conv = [](int64_t in, int64_t out) {
            return nn::Conv2d(nn::Conv2dOptions(in, out, 3).stride(2).padding(1));
        };
        photoEncoder = register_module(
            "photo_encoder",
            nn::Sequential(conv(3, 16), nn::ReLU(), conv(16, kPhotoChannels), nn::ReLU(),
                           conv(kPhotoChannels, kPhotoChannels), nn::ReLU(),
                           conv(kPhotoChannels, kPhotoChannels), nn::ReLU()));
        photoToCells = register_module("photo_to_cells",
                                       nn::Linear(kPhotoChannels * kPhotoRows * kPhotoColumns, 32));
    }
    if (classifiesPhoto) {
        namespace nn = torch::nn;
        photoCells = register_module(
            "photo_cells",
            nn::Sequential(nn::Linear(kPhotoChannels * kPhotoRows * kPhotoColumns, 128), nn::ReLU(),
                           nn::Dropout(kPhotoCellsDropout),
                           nn::Linear(128, kEmitterCellsPerSide * kEmitterCellsPerSide *
                                               kEmitterCellsPerSide)));
        // Silent at the start: a head that was not pretrained begins as one without it.
        torch::NoGradGuard noGrad;
        auto last = photoCellsOutput();
        last->weight.zero_();
        last->bias.zero_();
    }
    down2 = register_module("down2", PreActConv(16, 32, 2));
    mix = register_module("mix", PreActConv(32, 32, 1));
    where = register_module("where", torch::nn::Conv3d(torch::nn::Conv3dOptions(32, k, 1)));
    what = register_module("what", torch::nn::Linear(32, 6 * k));
    torch::NoGradGuard noGrad;
    // Small outputs at the start: positions near the middle of level 0, every emitter exactly
    // as dim. The small random weights elsewhere keep the emitters apart: identical ones would
    // get identical gradients and never separate.
    where->weight.mul_(0.1);
    where->bias.zero_();
    what->weight.mul_(0.1);
    what->weight.view({k, 6, -1}).select(1, 2).zero_();
    what->bias.zero_();
    what->bias.view({k, 6}).select(1, 2).fill_(kStartOpacityLogit);
}

Emitters EmitterHeadImpl::forward(const torch::Tensor& level0, const VolumeLayout& layout,
                                  const torch::Tensor& photoLuminance, const torch::Tensor& photo) {
    const auto cube = level0.detach();
    const auto centres = centresLike(layout, 0, cube).permute({3, 0, 1, 2}).unsqueeze(0);
    auto x = torch::cat({radianceFeature(cube.narrow(1, 0, 3).clamp_min(0)), cube.narrow(1, 3, 1),
                         centres / kPositionUnit},
                        1);
    x = F::adaptive_avg_pool3d(x, F::AdaptiveAvgPool3dFuncOptions(kReadResolution));
    auto features = down2(down1(x));  // [1, 32, 8, 8, 8]
    torch::Tensor places;             // the photo encoder's output, [1, channels x rows x columns]
    if (readsPhoto) {
        places = photoPlaces(photo);
        features = features + photoToCells(places).reshape({1, -1, 1, 1, 1});
    }
    features = mix(features);

    Emitters e;
    const auto cellCentres =
        F::adaptive_avg_pool3d(centres, F::AdaptiveAvgPool3dFuncOptions(kEmitterCellsPerSide))
            .reshape({3, kEmitterCellsPerSide * kEmitterCellsPerSide * kEmitterCellsPerSide})
            .t();                                         // [cells, 3]
    e.cellLogits = where(features).reshape({count, -1});  // [K, cells]
    if (classifiesPhoto) e.cellLogits = e.cellLogits + photoCells->forward(places);
    const auto weights =
        placesApart ? apartPeakWeights(kPeakSharpness * e.cellLogits, kEmitterCellsPerSide)
                    : torch::softmax(readsPhoto ? kPeakSharpness * e.cellLogits : e.cellLogits, 1);
    e.position = torch::matmul(weights, cellCentres);

    const auto out = what(features.mean({2, 3, 4})).reshape({count, 6});
    e.radius = kMinEmitterRadius +
               (kMaxEmitterRadius - kMinEmitterRadius) * torch::sigmoid(out.select(1, 0));
    e.alpha = torch::sigmoid(out.select(1, 2));
    const auto hue = 3.0 * torch::softmax(out.narrow(1, 3, 3), 1);  // mean 1 over the channels
    e.radiance = photoLuminance.reshape({1, 1}) *
                 hdrActivation(out.select(1, 1) + kStartLogBrightness).unsqueeze(1) * hue;
    return e;
}

torch::Tensor EmitterHeadImpl::photoPlaces(const torch::Tensor& photo) {
    TORCH_CHECK(photo.defined(), "a +photo emitter head needs the photo");
    // Each photo relative to its own mean luminance (floored at 1e-3), so that the exposure
    // does not matter, as ln(1 + x) like every radiance the networks read.
    const auto positive = photo.clamp_min(0);
    const auto meanLuminance = luminanceTensor(positive).mean({1, 2, 3}, true).clamp_min(1e-3);
    auto relative = radianceFeature(positive / meanLuminance);
    // A "+cells" head reads it at half size: where the lamps are is in the shading's large
    // scale, and its classifier generalised better so (held-out divergence after pretraining).
    if (classifiesPhoto) relative = F::avg_pool2d(relative, F::AvgPool2dFuncOptions(2));
    return F::adaptive_avg_pool2d(photoEncoder->forward(relative),
                                  F::AdaptiveAvgPool2dFuncOptions({kPhotoRows, kPhotoColumns}))
        .flatten(1);
}

torch::nn::Linear EmitterHeadImpl::photoCellsOutput() {
    TORCH_CHECK(classifiesPhoto, "only a +cells emitter head classifies the photo");
    return torch::nn::Linear(std::dynamic_pointer_cast<torch::nn::LinearImpl>(photoCells->ptr(3)));
}

torch::Tensor EmitterHeadImpl::photoCellLogits(const torch::Tensor& photo) {
    TORCH_CHECK(classifiesPhoto, "only a +cells emitter head classifies the photo");
    return photoCells->forward(photoPlaces(photo));
}

torch::Tensor apartPeakWeights(const torch::Tensor& sharpenedLogits, int64_t side) {
    const auto cell = torch::arange(
        side * side * side, torch::TensorOptions(torch::kLong).device(sharpenedLogits.device()));
    const auto z = cell.div(side * side, "floor"), y = cell.div(side, "floor").remainder(side),
               x = cell.remainder(side);
    auto open = torch::ones_like(cell, torch::kBool);
    std::vector<torch::Tensor> rows;
    for (int64_t k = 0; k < sharpenedLogits.size(0); ++k) {
        if (!open.any().item<bool>()) open.fill_(true);
        const auto logits = sharpenedLogits[k].masked_fill(open.logical_not(),
                                                           -std::numeric_limits<float>::infinity());
        rows.push_back(torch::softmax(logits, 0));
        const int64_t peak = logits.argmax().item<int64_t>();
        const auto near =
            (z - z[peak]).abs().le(1) & (y - y[peak]).abs().le(1) & (x - x[peak]).abs().le(1);
        open = open & near.logical_not();
    }
    return torch::stack(rows);
}

std::vector<torch::Tensor> addEmitters(const std::vector<torch::Tensor>& cubes,
                                       const Emitters& emitters, const VolumeLayout& layout) {
    std::vector<torch::Tensor> out;
    const int64_t k = emitters.position.size(0);
    for (size_t level = 0; level < cubes.size(); ++level) {
        const auto& cube = cubes[level];
        const int64_t r = cube.size(2);
        const double voxel = layout.voxelSize(int(level));
        const auto centres = centresLike(layout, int(level), cube).reshape({-1, 1, 3});
        const auto width = emitters.radius.clamp_min(kMinEmitterWidthVoxels * voxel);  // [K]
        const auto distance2 = (centres - emitters.position.reshape({1, k, 3})).pow(2).sum(-1);
        const auto blobAlpha = emitters.alpha.reshape({1, k}) *
                               torch::exp(-distance2 / (2.0 * width.pow(2)).reshape({1, k}));
        // Optical depth over one voxel (the density in voxel units), per voxel and emitter:
        // [R^3, K].
        const auto blobDepth = densityFromAlpha(blobAlpha, 1.0);
        const auto blobRadiance =
            emitters.radiance * (emitters.radius / width).pow(2).unsqueeze(1);  // [K, 3]
        const auto emitterDepth = blobDepth.sum(1).reshape({1, 1, r, r, r});
        const auto emitterLight =
            torch::matmul(blobDepth, blobRadiance).t().reshape({1, 3, r, r, r});

        const auto rgb = cube.narrow(1, 0, 3), alpha = cube.narrow(1, 3, 1);
        const auto cubeDepth = densityFromAlpha(alpha, 1.0);
        const auto depth = cubeDepth + emitterDepth;
        const auto mixed = (cubeDepth * rgb + emitterLight) / depth.clamp_min(1e-12);
        out.push_back(
            torch::cat({torch::where(depth > 1e-12, mixed, rgb), 1.0 - torch::exp(-depth)}, 1));
    }
    return out;
}

}  // namespace lh::net
