// The emitter head: a few compact lamps placed by the network, beside what the completion
// networks paint (a "+emitters" configuration, net/config.h).
//
// Most of the light a predicted envmap misses comes from lamps and windows that the photo does
// not show (docs/network.md, "Where the error is"). A completion network answers a lamp it
// cannot place with a dim glow spread over the walls, which the per-pixel losses then charge
// for. The head instead places K small bright blobs in the room. Each has a position (a soft
// argmax over the 8^3 cells of level 0), a radius, a peak opacity and an HDR colour, and is
// added to every level as a Gaussian blob of density. Its light is compact by construction, so
// making it brighter costs few pixels, and the irradiance loss can move it smoothly towards
// the side the light comes from.
//
// The lamps a photo does not show can be placed only from the shading they cast on what it
// does show. A "+photo" head (NetConfig::emitterPhoto) therefore also reads the reference
// photo through a small 2D encoder, and is trained as a classifier: its distribution over
// level 0's cells against the cells of the scene's true lamps and windows (net/losses.h
// emitterCellLoss). A squared distance would teach the mean of where lamps may be, which is
// nowhere in particular; a distribution keeps the places apart, and each lamp sits at the peak
// of its own (a sharpened soft argmax), not at its mean.
//
// Where the lamps share one distribution (a "+cells" classifier's logits dominate every
// lamp's), all of them find its one peak, and one place cannot carry a room's unseen light,
// which comes from several lamps and windows. A "+apart" head (NetConfig::emitterApart) places
// them in turn: each at the sharpened peak of the cells that are not next to (within one cell,
// diagonals included) an earlier lamp's peak. The choice of cells is not differentiable; the
// position within the chosen ones is, as before.
#pragma once

#include "net/torch_pch.h"
#include "net/unet3d.h"
#include "vdb/volume_layout.h"

#include <vector>

namespace lh::net {

// Emitter radii the head may choose, metres: from a small bulb to a window-sized panel.
constexpr double kMinEmitterRadius = 0.05;
constexpr double kMaxEmitterRadius = 0.5;
// A blob is never drawn narrower than this many voxels of the level it lies in (standard
// deviation of its Gaussian), so that it does not vanish between voxel centres; its radiance
// falls with the square of the widening, so it sends the same light at every level.
constexpr double kMinEmitterWidthVoxels = 0.7;

struct Emitters {
    torch::Tensor position;  // [K, 3] metres, the volume's frame (the reference camera's)
    torch::Tensor radius;    // [K] metres: the Gaussian's standard deviation
    torch::Tensor alpha;     // [K] voxel opacity at the centre, in (0, 1)
    torch::Tensor radiance;  // [K, 3] linear RGB
    // Each lamp's position logits over level 0's 8^3 cells [K, cells] (z-major, like the
    // cubes): what the cell loss reads.
    torch::Tensor cellLogits;
};

// Level 0's cells per side, over which the head places its lamps: two stride-2 stages below
// the 32^3 at which it reads level 0.
constexpr int64_t kEmitterCellsPerSide = 8;

// A "+photo" head places each lamp at softmax(kPeakSharpness x logits) over the cells: near the
// peak of its distribution, still differentiable.
constexpr double kPeakSharpness = 4.0;

struct EmitterHeadImpl : torch::nn::Module {
    // readsPhoto: the "+photo" design (NetConfig::emitterPhoto); classifiesPhoto: "+cells"
    // (NetConfig::emitterPhotoCells, with readsPhoto); placesApart: "+apart"
    // (NetConfig::emitterApart, with readsPhoto).
    EmitterHeadImpl(int count, bool readsPhoto, bool classifiesPhoto = false,
                    bool placesApart = false);
    // level0: the completed level-0 cube [1, 4, R, R, R] (R a multiple of 16; read, not
    // trained through); photoLuminance: the photo's mean linear luminance, a scalar tensor
    // (the emitters' radiance is relative to it, so a brighter exposure brightens them too);
    // photo: the linear reference image [1, 3, H, W] (H, W multiples of 16), read only by a
    // "+photo" head, relative to its own mean luminance (it may be the photo before its clip at
    // 1, NetConfig::emitterPhotoUnclipped, while photoLuminance is the clipped photo's).
    Emitters forward(const torch::Tensor& level0, const VolumeLayout& layout,
                     const torch::Tensor& photoLuminance, const torch::Tensor& photo = {});

    // "+cells": the logits over level 0's 8^3 cells [1, cells] of where lamps are, from the
    // photo alone (its encoder and photoCells), as forward adds them to every lamp's. The
    // photos [N, 3, H, W] as forward takes one.
    torch::Tensor photoCellLogits(const torch::Tensor& photo);
    // "+cells": the classifier's last layer (one logit per cell).
    torch::nn::Linear photoCellsOutput();

    int count;
    bool readsPhoto, classifiesPhoto, placesApart;
    PreActConv down1{nullptr}, down2{nullptr}, mix{nullptr};
    // "+photo": four stride-2 convolutions over the photo, pooled to 3 x 4 places and mapped to
    // one feature vector that every cell sees.
    torch::nn::Sequential photoEncoder{nullptr};
    torch::nn::Linear photoToCells{nullptr};
    // "+cells": the photo encoder's places -> 128 features (dropout 0.3) -> one logit per cell.
    torch::nn::Sequential photoCells{nullptr};

    torch::nn::Conv3d where{nullptr};  // one position logit per emitter and 8^3 cell
    torch::nn::Linear what{nullptr};   // per emitter: radius, brightness, opacity, colour (3)

private:
    // The photo encoder's output for a photo [N, 3, H, W]: [N, channels x rows x columns].
    torch::Tensor photoPlaces(const torch::Tensor& photo);
};
TORCH_MODULE(EmitterHead);

// "+apart": the weights over a cube of cells per side^3 cells (z, y, x order) that place each
// lamp, from its sharpened logits [K, cells]: lamp k's softmax over the cells not within one
// cell of an earlier lamp's peak, 0 on the others. Where every cell is taken (more lamps than
// fit), the next lamp may use them all again.
torch::Tensor apartPeakWeights(const torch::Tensor& sharpenedLogits, int64_t side);

// The cubes [1, 4, R, R, R] (linear RGB, voxel alpha) of `layout` with the emitters added: in
// every voxel the optical depths add and the colours mix in proportion to them, as two
// emission-absorption media sharing the voxel do.
std::vector<torch::Tensor> addEmitters(const std::vector<torch::Tensor>& cubes,
                                       const Emitters& emitters, const VolumeLayout& layout);

}  // namespace lh::net
