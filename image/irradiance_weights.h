// The weights of the diffuse-irradiance metric (image/metrics.h): how much each pixel of an
// equirectangular envmap adds to the irradiance at each axis normal. One table for the metric
// and for the network's irradiance loss (net/losses.h), which integrates with it in torch.
#pragma once

#include "image/metrics.h"

#include <vector>

namespace lh {

// Weight of pixel p = r W + c for normal n (AxisNormal order) at index p * kAxisNormals + n:
// max(0, n.d) dOmega, d the pixel's direction and dOmega = (2 pi / W)(pi / H) sin(phi) its
// solid angle (sr). E(n) = sum over p of L(p) weight(p, n); a constant L = 1 gives about pi.
// Throws InputError for a size below 1x1.
std::vector<double> axisIrradianceWeights(int width, int height);

}  // namespace lh
