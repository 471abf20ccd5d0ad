// Sizes of the prediction pipeline. Four named configurations share every line of code:
//   `standard` (the default): the paper's 5 x 64^3 volume from a 192x144 input with 32 planes,
//              with a 2D MPI network over the plane-sweep volume and completion networks that
//              run at 32^3 and are blended into the full-resolution cubes, HDR radiance;
//   `wide`:    `standard` with completion networks of twice the channels (8 .. 128), the
//              capacity the unseen walls, lamps and windows ask for; its MPI network has
//              `standard`'s parameters, so it can start from a `standard` model;
//   `paper`:   the paper's sizes and 3D networks throughout;
//   `small`:   the first bundled model's sizes (64x48 input, 4 x 16^3, colours in [0, 1]).
// Torch-free: the CLI and tests read it without libtorch.
#pragma once

#include <string>

namespace lh::net {

// Largest highlight gain a model or a user may ask for (net/highlight_gain.h): 1000 already
// makes a voxel at 1.1 times white a lamp of 100.
constexpr double kMaxHighlightGain = 1000.0;
// Largest knee (net/highlight_gain.h): a luminance of 100 is already a lamp in any exposure.
constexpr double kMaxHighlightKnee = 100.0;

// Emitters of a "+emitters" configuration: the training rooms have 1-3 ceiling lights and 1-3
// windows, of which the photo shows some.
constexpr int kSuffixEmitters = 3;
constexpr int kMaxEmitters = 16;

struct NetConfig {
    std::string name = "small";
    int width = 128;      // network input width, pixels (multiple of 16: four stride-2 stages)
    int height = 96;      // network input height, pixels (multiple of 16)
    int planes = 16;      // MPI / plane-sweep planes D (multiple of 16)
    int levels = 5;       // nested cubes L
    int resolution = 32;  // voxels per cube side R (multiple of 16)
    int baseWidth = 8;    // channels of the first encoder stage (the paper's 8)
    // Training renderer: envmap size and samples per level along each ray.
    int trainEnvWidth = 60;
    int trainEnvHeight = 30;
    int samplesPerLevel = 64;
    // The MPI network: "3d" (a 3D U-Net over planes x rows x columns, the paper's) or "2d" (a
    // 2D U-Net whose channels are the plane-sweep volume's planes; far cheaper per pixel).
    std::string mpiNetwork = "3d";
    int mpiWidth = 32;  // first-stage channels of the 2D MPI network
    // The completion networks run at resolution / completionScale voxels per side (1 or 2);
    // at 2 their output is upsampled and blended into the full-resolution cube.
    int completionScale = 1;
    int completionResolution() const { return resolution / completionScale; }
    // Colour activation: false: sigmoid, radiance in [0, 1]; true: HDR (net/hdr.h), unbounded
    // positive radiance, and the MPI may brighten the photo where it saturates.
    bool hdr = false;
    // HDR only. Colours the networks invent (the MPI's background, the completed voxels) are
    // relative to the photo's mean linear colour: exp(logit) times that mean, so that an
    // untrained or uncertain network paints the room in the photo's own hue and exposure, and a
    // brighter exposure of the same photo brightens the whole volume by the same factor.
    bool colourAnchor = false;
    // The completion networks also see the observed colour at each height of the room
    // (net/height_profile.h): 4 more input channels each. Named by a "+profile" suffix.
    bool heightProfile = false;
    // Lamps placed by an emitter head beside the completion networks (net/emitter_head.h):
    // how many; 0 for none. Named by a "+emitters" suffix (kSuffixEmitters of them).
    int emitters = 0;
    // The emitter head also reads the reference photo (the shading the room's lamps cast on
    // what it shows) and places each lamp at the peak of its distribution over level 0's cells,
    // not at the distribution's mean (net/emitter_head.h). Named by a "+photo" suffix, with
    // "+emitters".
    bool emitterPhoto = false;
    // The photo head also has a classifier of where lamps are from the photo alone, whose cell
    // logits add to every lamp's, and which `train --pretrain-lamp-cells` trains on photos
    // before the fine-tuning (net/lamp_cell_pretraining.h). Named by a "+cells" suffix, with
    // "+emitters+photo".
    bool emitterPhotoCells = false;
    // The photo head's lamps take different places: each in turn at the peak of the cells not
    // next to an earlier lamp's (net/emitter_head.h). Without it, lamps that share the
    // classifier's logits all sit at its one peak. Named by a "+apart" suffix, with
    // "+emitters+photo".
    bool emitterApart = false;
    // The photo head reads the reference photo's radiance before the clip at 1 where the input
    // keeps it: a linear EXR photo (PairInputs::refUnclipped), and in training each example's
    // unclipped render, exposed as its photo was. The brightest pixels' magnitudes (lamps and
    // their reflections) say where the lamps the photo does not show are, which a clipped photo
    // loses. Everything else reads the clipped photo, as before. Named by a "+unclipped" suffix,
    // with "+emitters+photo".
    bool emitterPhotoUnclipped = false;
    // Voxel alpha below which the model's volumes are left empty: the threshold it was trained
    // under (train --prune-alpha), so predict prunes there by default and the walls it learnt
    // to make opaque survive. 0: trained unpruned; predict uses its own default.
    double pruneAlpha = 0;
    // What each voxel holds above white is multiplied by this when the volume is made
    // (net/highlight_gain.h): the gain it was trained under (train --highlight-gain), so predict
    // applies the same by default. 1: none.
    double highlightGain = 1;

    static NetConfig small();
    static NetConfig paper();
    static NetConfig standard();
    static NetConfig wide();
    // "standard", "wide", "small" or "paper", each optionally followed by "+profile"
    // (heightProfile on), "+emitters" (kSuffixEmitters emitters), "+photo" (emitterPhoto on,
    // with "+emitters"), "+cells" (emitterPhotoCells on, with "+photo"), "+apart"
    // (emitterApart on, with "+photo") and "+unclipped" (emitterPhotoUnclipped on, with
    // "+photo"), in any order; throws InputError otherwise.
    static NetConfig byName(const std::string& name);

    // Throws InputError naming the bad size.
    void validate() const;
    std::string toJson() const;
    // Whether a model of `other` has the same parameters (names and shapes) as one of this
    // configuration, so that `train --init` can fine-tune one into the other.
    bool sameParameters(const NetConfig& other) const;
    static NetConfig fromJson(const std::string& text, const std::string& sourceName);
};

}  // namespace lh::net
