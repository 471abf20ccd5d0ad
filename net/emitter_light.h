// How much light the emitter head's lamps send, and a loss that asks for the truth's.
//
// The head's lamps (net/emitter_head.h) learnt to be placed by the cell loss, but the envmap
// losses only ever told them "not like that", and every run put them out: below the opacity at
// which predict prunes, they vanish from the exported volume. This supervises their power
// directly. Each training envmap's pixels brighter than what a photo clips (luminance above 1:
// the lamps and windows, as `eval`'s highlights) that the photo did not see give the light the
// room's unseen emitters send to that point from each side; the lamps, as small sources, give
// theirs in closed form. The loss compares the two over the six axis normals and three
// channels as the irradiance metric does.
//
// A lamp is a Gaussian blob of voxel opacity (net/emitter_head.h addEmitters). Seen from afar
// it sends radiance times an effective area, its intensity J (linear radiance x m^2):
//   J = L' 2 pi w^2 Ein(A),
// w = max(r, kMinEmitterWidthVoxels v) its drawn width in the voxels of size v of the finest
// level that holds its centre (the level the renderer reads there), L' = L (r / w)^2 its drawn
// radiance, A = sqrt(2 pi) (w / v) Li_{3/2}(alpha) the optical depth along a ray through its
// centre, and Ein(A) = int_0^A (1 - e^-u) / u du (A for a faint lamp: J = L' (2 pi)^{3/2}
// w^3 alpha / v; ln A for an opaque one, whose light grows with its cross-section). Only its
// part above predict's pruning threshold survives export: the Gaussian's mass inside the
// radius where alpha g > t, the chi-3 distribution's share below u = sqrt(2 ln(alpha / t)).
// That share is smoothed below the threshold, so a lamp too faint to survive still learns
// that a higher opacity would show it.
#pragma once

#include "core/vec.h"
#include "net/emitter_head.h"
#include "net/torch_pch.h"
#include "vdb/volume_layout.h"

#include <vector>

namespace lh::net {

// Ein(A) = int_0^A (1 - e^-u) / u du for A >= 0, elementwise; differentiable.
torch::Tensor entireExponentialIntegral(const torch::Tensor& a);

// The share of a lamp's light that survives pruning at voxel alpha `threshold` (in (0, 1)),
// per lamp of peak alpha `alpha` [K]: the chi-3 distribution's mass below
// sqrt(2 softplus(ln(alpha / threshold))), the softplus letting a lamp just below the threshold
// keep a small share and a gradient. threshold 0: 1 (nothing pruned).
torch::Tensor survivingShare(const torch::Tensor& alpha, double threshold);

// Each lamp's intensity J [K, 3] (linear radiance x m^2, per RGB channel), as exported with
// pruning at `pruneThreshold` (0: unpruned). See the header comment.
torch::Tensor emitterIntensity(const Emitters& emitters, const VolumeLayout& layout,
                               double pruneThreshold);

// The irradiance [3, 6] (RGB; normals +x, -x, +y, -y, +z, -z, as axisIrradianceTensor) that
// lamps of intensity [K, 3] at emitters.position send to `point` (metres, the volume's frame),
// each as a small source: J max(0, n . d) / (|x - point|^2 + r^2), r its radius, so a point
// inside a lamp stays finite. Occlusion by the room is not modelled.
torch::Tensor emitterAxisIrradiance(const Emitters& emitters, const torch::Tensor& intensity,
                                    const Vec3d& point);

// The irradiance [3, 6] of the pixels of a linear envmap [1, 3, H, W] brighter than luminance 1
// (the lamps and windows a photo clips) and, where `observed` [1, 1, H, W] (1 where the photo
// saw the pixel) is given, not observed; the others counting as black.
torch::Tensor highlightAxisIrradiance(const torch::Tensor& envmap,
                                      const torch::Tensor& observed = {});

// The emitter light loss of one example's envmaps [1, 3, H, W] seen from `points` (one each),
// their mean: per envmap, the mean over the three channels and six normals of f(r), r = (e +
// predicted) / (e + truth), f(r) = -ln r below 1 and r - 1 above; predicted =
// emitterAxisIrradiance, truth = highlightAxisIrradiance(envmap, observed) (the lamps and
// windows the photo did not see: the MPI shows those it saw; `observed` may be shorter than
// `envmaps`, or empty, where envmaps have no mask), e per channel a twentieth of the envmap's
// whole mean axis irradiance (light that small does not move the irradiance metric).
// 0 when the lamps send the unseen highlights' light, in its colour, from every side. Short of
// it, a lamp is pulled up on a log scale, as strongly when too faint to show as when half as
// bright as it should be; beyond it, the cost grows with all the light it adds, as in the
// irradiance metric, so that where a lamp's side is uncertain it does not overshoot. The
// lamps' intensities are emitterIntensity's (pruned at `pruneThreshold`), their positions and
// radii read, not trained: where they are is the lamp-cell loss's to teach and how large the
// envmap losses', how much light they send from there (radiance and opacity) this loss's.
torch::Tensor emitterLightLoss(const Emitters& emitters, const VolumeLayout& layout,
                               double pruneThreshold, const std::vector<Vec3d>& points,
                               const std::vector<torch::Tensor>& envmaps,
                               const std::vector<torch::Tensor>& observed = {});

}  // namespace lh::net
