#include "net/emitter_light.h"

#include "image/luminance.h"
#include "net/losses.h"
#include "net/tensor_image.h"

#include <cmath>

namespace lh::net {

namespace {

// Ein's quadrature: Ein(A) = int_0^inf (1 - exp(-A e^-s)) ds, whose integrand falls from about
// 1 to A e^-s around s = ln A, sampled on [0, kEinSpan] (A up to e^20 is exact to the step's
// accuracy) plus the tail A e^-kEinSpan in closed form. An odd count, for Simpson's rule.
constexpr double kEinSpan = 30.0;
constexpr int64_t kEinSamples = 241;
// The loss's floor: this share of the envmap's whole mean axis irradiance, per channel (light
// that small does not move the irradiance metric).
constexpr double kLightFloorShare = 0.05;
// Terms of the polylogarithm Li_{3/2}(alpha) = sum alpha^n / n^1.5 (alpha < 1).
constexpr int kPolylogTerms = 40;
// The softplus' sharpness (per unit of ln(alpha / t)) that smooths the surviving share.
constexpr double kThresholdSoftness = 4.0;

// The finest level whose box holds `p` (level 0 where none does: the lamp is drawn there too).
int finestLevelHolding(const VolumeLayout& layout, const Vec3d& p) {
    for (int level = layout.levels - 1; level > 0; --level)
        if (layout.box(level).contains(p)) return level;
    return 0;
}

torch::Tensor polylogThreeHalves(const torch::Tensor& alpha) {
    auto sum = torch::zeros_like(alpha);
    auto power = torch::ones_like(alpha);
    for (int n = 1; n <= kPolylogTerms; ++n) {
        power = power * alpha;
        sum = sum + power / std::pow(double(n), 1.5);
    }
    return sum;
}

}  // namespace

torch::Tensor entireExponentialIntegral(const torch::Tensor& a) {
    const auto s = torch::linspace(0.0, kEinSpan, kEinSamples, a.options());
    const auto x = a.unsqueeze(-1) * torch::exp(-s);  // [..., samples]
    const auto f = -torch::expm1(-x);                 // 1 - e^-x, exact for small x
    // Simpson's rule (an even number of steps): weights 1, 4, 2, 4, ..., 2, 4, 1 times step / 3.
    const double step = kEinSpan / double(kEinSamples - 1);
    auto weights = torch::full({kEinSamples}, 2.0, a.options());
    weights.slice(0, 1, kEinSamples, 2).fill_(4.0);
    weights[0] = 1.0;
    weights[kEinSamples - 1] = 1.0;
    return (step / 3.0) * (f * weights).sum(-1) + a * std::exp(-kEinSpan);
}

torch::Tensor survivingShare(const torch::Tensor& alpha, double threshold) {
    if (threshold <= 0) return torch::ones_like(alpha);
    const auto above = torch::log(alpha.clamp_min(1e-12) / threshold);
    const auto soft = torch::softplus(above, kThresholdSoftness).clamp_min(1e-12);
    const auto u = torch::sqrt(2.0 * soft);
    // The chi distribution with three degrees of freedom: the mass of a 3D Gaussian inside u
    // standard deviations.
    return torch::erf(u / std::sqrt(2.0)) - std::sqrt(2.0 / M_PI) * u * torch::exp(-0.5 * u * u);
}

torch::Tensor emitterIntensity(const Emitters& emitters, const VolumeLayout& layout,
                               double pruneThreshold) {
    const int64_t k = emitters.position.size(0);
    const auto where = emitters.position.detach().to(torch::kCPU, torch::kFloat64);
    std::vector<double> voxel(static_cast<size_t>(k));
    for (int64_t i = 0; i < k; ++i) {
        const Vec3d p{where[i][0].item<double>(), where[i][1].item<double>(),
                      where[i][2].item<double>()};
        voxel[size_t(i)] = layout.voxelSize(finestLevelHolding(layout, p));
    }
    const auto v = torch::tensor(voxel, emitters.radius.options());
    const auto width = torch::maximum(emitters.radius, kMinEmitterWidthVoxels * v);
    const auto depth = std::sqrt(2.0 * M_PI) * (width / v) * polylogThreeHalves(emitters.alpha);
    // J = L' 2 pi w^2 Ein(A) with L' = L (r / w)^2: the width cancels outside A.
    const auto perRadiance = 2.0 * M_PI * emitters.radius.pow(2) *
                             entireExponentialIntegral(depth) *
                             survivingShare(emitters.alpha, pruneThreshold);
    return emitters.radiance * perRadiance.unsqueeze(1);
}

torch::Tensor emitterAxisIrradiance(const Emitters& emitters, const torch::Tensor& intensity,
                                    const Vec3d& point) {
    const auto origin =
        torch::tensor({point.x(), point.y(), point.z()}, emitters.position.options()).view({1, 3});
    const auto offset = emitters.position - origin;                             // [K, 3]
    const auto distance = offset.norm(2, 1, /*keepdim=*/true).clamp_min(1e-6);  // [K, 1]
    const auto direction = offset / distance;
    const auto cosines =
        torch::stack({direction.select(1, 0), -direction.select(1, 0), direction.select(1, 1),
                      -direction.select(1, 1), direction.select(1, 2), -direction.select(1, 2)},
                     1)
            .clamp_min(0.0);                                                    // [K, 6]
    const auto spread = distance.pow(2) + emitters.radius.pow(2).unsqueeze(1);  // [K, 1] m^2
    // [K, 3, 1] x [K, 1, 6] summed over the lamps.
    return (intensity.unsqueeze(2) * (cosines / spread).unsqueeze(1)).sum(0);
}

torch::Tensor highlightAxisIrradiance(const torch::Tensor& envmap, const torch::Tensor& observed) {
    auto bright = (luminanceTensor(envmap) > kLampLuminance).to(envmap.scalar_type());
    if (observed.defined()) bright = bright * (1.0 - observed.to(bright.options()));
    return axisIrradianceTensor(envmap.clamp_min(0.0) * bright).reshape({3, 6});
}

torch::Tensor emitterLightLoss(const Emitters& emitters, const VolumeLayout& layout,
                               double pruneThreshold, const std::vector<Vec3d>& points,
                               const std::vector<torch::Tensor>& envmaps,
                               const std::vector<torch::Tensor>& observed) {
    TORCH_CHECK(!envmaps.empty() && points.size() == envmaps.size(),
                "emitterLightLoss needs one point per envmap");
    // Where the lamps are is the cell loss's to teach, and how large the envmap losses'; this
    // one reads both and asks only how much light the lamps send from there (their radiance
    // and opacity), so that a lamp facing the truth's light brightens and one facing none
    // dims, without pulling either towards the highlights' average direction or swelling it
    // into a glowing ball whose light is cheap here and costly in every pixel it covers.
    Emitters placed = emitters;
    placed.position = emitters.position.detach();
    placed.radius = emitters.radius.detach();
    // The same lamps light every envmap: their intensity once.
    const auto intensity = emitterIntensity(placed, layout, pruneThreshold);
    auto total = torch::zeros({}, intensity.options());
    for (size_t k = 0; k < envmaps.size(); ++k) {
        const auto truth = highlightAxisIrradiance(
            envmaps[k], k < observed.size() ? observed[k] : torch::Tensor());
        const auto whole = axisIrradianceTensor(envmaps[k].clamp_min(0.0)).reshape({3, 6});
        const auto floor = kLightFloorShare * whole.mean(1, /*keepdim=*/true) + 1e-6;  // [3, 1]
        const auto predicted = emitterAxisIrradiance(placed, intensity, points[k]);
        // Short of the truth, the log of the ratio: a lamp too faint to show is pulled up as
        // strongly as one half as bright as it should be. Beyond it, the ratio less 1, which
        // grows with all the light a lamp adds: where its side is uncertain, overshooting costs
        // more than falling short, as it does in the irradiance metric. Both are 0 with slope 1
        // at the truth.
        const auto ratio = (floor + predicted) / (floor + truth);
        total = total + torch::where(ratio < 1.0, -torch::log(ratio), ratio - 1.0).mean();
    }
    return total / double(envmaps.size());
}

}  // namespace lh::net
