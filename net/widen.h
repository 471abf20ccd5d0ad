// Function-preserving widening (Net2Net's "wider" move): a 3D U-Net of base width 2w that
// computes what one of base width w computes, so a `wide` model starts where a `standard` one
// ended instead of from random completion networks.
//
// Every widened channel c of the narrow network becomes two channels, c and c + C (C its old
// count), holding the same activation: a convolution's output filters and biases and a norm's
// gain and bias are copied to both. A convolution reading a widened input splits each weight
// w of the narrow one in two, w (1/2 + d) and w (1/2 - d), with d drawn uniformly in
// [-split, split] per weight: the two halves sum to w, so the output is unchanged, while
// their difference lets the two copies learn apart (with d = 0 they would get identical
// gradients forever). ChannelLayerNorm normalises over channels and voxels together, and a
// channel list of exact duplicates has the same mean and variance, so the norms are unchanged
// too. The decoder's concatenation [upsampled, skip] becomes [upsampled x 2, skip x 2], and
// its merge convolution reads it in that order.
#pragma once

#include "net/lighthouse_net.h"
#include "net/unet3d.h"

namespace lh::net {

// Sets `wide`'s parameters from `narrow` (base widths 2w and w, same input and output
// channels); throws InputError if the shapes are not those of such a pair.
void widenUNet3d(UNet3d& wide, const UNet3d& narrow, int narrowBaseWidth, double split);

// Widens every completion network of `narrow` into `wide` (configurations equal but for a base
// width twice as large) and copies every other parameter. Throws InputError otherwise.
void widenModel(LighthouseNet& wide, LighthouseNet& narrow, double split = 0.25);

}  // namespace lh::net
