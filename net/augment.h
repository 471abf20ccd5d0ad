// Training-time augmentation of an example, so that the network sees what users' cameras
// give: other exposures and white balances, sensor noise, and 8-bit quantisation after it.
//
// The photos are what a camera saved: linear radiance times exposure and per-channel gain,
// clipped at 1, with Gaussian noise added in sRGB (8-bit) code values, then quantised to 8
// bits, and for half of the examples saved as JPEG (quality 60-95) and read back, as phones
// save their photos. Exposure and white balance change the scene's light as a whole, so every HDR
// target (envmaps, the oracle's colours) is scaled by the same factors, unclipped.
#pragma once

#include "core/random.h"
#include "image/image.h"

namespace lh::net {

struct Augmentation {
    double exposure = 1.0;             // multiplies radiance
    double gain[3] = {1.0, 1.0, 1.0};  // white balance, per channel
    double noiseSigma = 0.0;           // in sRGB code values / 255
    int jpegQuality = 0;               // 1-100: the photos go through JPEG at it; 0: not
    double factor(int channel) const { return exposure * gain[channel]; }
};

// Exposure e^U(-0.6, 0.6) (0.55x-1.8x), gains e^U(-0.12, 0.12), noise sigma U(0, 2.5)/255,
// JPEG at quality U{60..95} for half of the draws.
Augmentation drawAugmentation(Random& rng);

// An 8-bit sRGB encoding of `linear` (values in [0, 1]) saved as JPEG at `quality` and decoded
// again, back in linear: what a photo loses to JPEG (8x8 blocks, chroma subsampling).
ImageRGB jpegRoundTrip(const ImageRGB& linear, int quality);

// A photo (linear, decoded from 8-bit sRGB): scaled, clipped at 1, noisy, re-quantised.
void augmentPhoto(ImageRGB& photo, const Augmentation& a, Random& rng);
// An HDR target: scaled only.
void augmentRadiance(ImageRGB& radiance, const Augmentation& a);

}  // namespace lh::net
