// The emitter head's light in closed form (net/emitter_light.h) against known answers: Ein's
// values, the share of a blob that survives pruning, a lamp's irradiance against the envmap the
// renderer draws of it (faint, opaque and pruned), an envmap's highlights, and a loss that asks
// a dark lamp for light where the truth has some, a bright one for less where it has none, and
// a white one for the truth's colour.
#include "net/emitter_light.h"
#include "net/losses.h"
#include "net/tensor_image.h"
#include "net/volume_render.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh::net {
namespace {

// One level of 8 m in 32^3 voxels of 0.25 m, centred on the origin.
const VolumeLayout kLayout{8.0, 1, 32};

Emitters lampAt(const Vec3d& p, double radius, double alpha, double radiance) {
    Emitters e;
    e.position = torch::tensor({float(p.x()), float(p.y()), float(p.z())}).reshape({1, 3});
    e.radius = torch::tensor({float(radius)});
    e.alpha = torch::tensor({float(alpha)});
    e.radiance = torch::full({1, 3}, float(radiance));
    return e;
}

// The axis irradiance [3, 6] of the envmap the renderer draws at the origin of the lamp alone
// (pruned at `threshold`, 0: not). At 180x90 pixels and 96 samples the ratios below are those
// at 360x180 and 192 within 3e-4 (and 1.2 s against 15 s).
torch::Tensor renderedAxisIrradiance(const Emitters& e, double threshold) {
    std::vector<torch::Tensor> cubes = addEmitters({torch::zeros({1, 4, 32, 32, 32})}, e, kLayout);
    if (threshold > 0) cubes = pruneCubesStraightThrough(cubes, threshold);
    const auto envmap = renderEnvmapTorch(cubes, kLayout, Vec3d(0.0, 0.0, 0.0), 180, 90, 96);
    return axisIrradianceTensor(envmap).reshape({3, 6});
}

double at(const torch::Tensor& t, int64_t i) { return t[i].item<double>(); }
// Channel c's irradiance on normal `axis` of a [3, 6] table.
double at(const torch::Tensor& t, int64_t c, int64_t axis) { return t[c][axis].item<double>(); }

TEST(EmitterLight, EinHasItsKnownValues) {
    // Ein(x) = E1(x) + gamma + ln x: Ein(1) = 0.7965996, Ein(10) = 2.8798049.
    const auto ein =
        entireExponentialIntegral(torch::tensor({0.0, 1e-4, 1.0, 10.0, 1000.0}, torch::kFloat64));
    EXPECT_NEAR(at(ein, 0), 0.0, 1e-12);
    EXPECT_NEAR(at(ein, 1), 1e-4 * (1 - 1e-4 / 4), 1e-8);
    EXPECT_NEAR(at(ein, 2), 0.7965996, 1e-4);
    EXPECT_NEAR(at(ein, 3), 2.8798049, 1e-4);
    EXPECT_NEAR(at(ein, 4), std::log(1000.0) + 0.5772157, 1e-3);
}

TEST(EmitterLight, TheShareThatSurvivesPruning) {
    const auto alpha = torch::tensor({0.001, 0.03, 0.09, 0.9}, torch::requires_grad());
    EXPECT_TRUE(torch::allclose(survivingShare(alpha, 0.0), torch::ones({4})));
    const auto share = survivingShare(alpha, 0.03);
    // Far below the threshold next to nothing survives; at three times it, the chi-3 mass
    // below sqrt(2 ln 3) = 1.48 standard deviations (0.47); far above, nearly all.
    EXPECT_LT(at(share, 0), 1e-4);
    EXPECT_LT(at(share, 1), 0.1);
    EXPECT_NEAR(at(share, 2), 0.468, 0.01);
    EXPECT_GT(at(share, 3), 0.9);
    EXPECT_LT(at(share, 0), at(share, 1));
    EXPECT_LT(at(share, 1), at(share, 2));
    // A lamp just below the threshold still learns that more opacity would show it.
    share.sum().backward();
    EXPECT_GT(alpha.grad()[1].item<double>(), 0.0);
    EXPECT_GT(alpha.grad()[0].item<double>(), 0.0);
}

TEST(EmitterLight, ALampsIrradianceIsWhatTheRendererDrawsOfIt) {
    struct Case {
        const char* name;
        double radius, alpha, threshold, tolerance;
    };
    // A faint blob, an opaque one (whose light the optical depth's Ein caps), and one pruned
    // where it is fainter than a third of its peak. The closed form takes an opaque blob's
    // cross-section as Gaussian in optical depth (it is flatter) and ignores how trilinear
    // interpolation halves the voxels at the pruned edge of a blob a voxel wide: within 25%.
    const Case cases[] = {{"faint", 0.3, 0.1, 0.0, 0.08},
                          {"opaque", 0.4, 0.95, 0.0, 0.25},
                          {"pruned", 0.3, 0.3, 0.1, 0.25}};
    for (const Case& c : cases) {
        // 2 m along +x of the point, orange: its light falls on the +x normal in its colour,
        // none on -x.
        Emitters e = lampAt(Vec3d(2.0, 0.0, 0.0), c.radius, c.alpha, 20.0);
        e.radiance = torch::tensor({20.f, 10.f, 5.f}).reshape({1, 3});
        const auto predicted =
            emitterAxisIrradiance(e, emitterIntensity(e, kLayout, c.threshold), Vec3d(0, 0, 0));
        const auto rendered = renderedAxisIrradiance(e, c.threshold);
        for (int64_t channel = 0; channel < 3; ++channel) {
            EXPECT_GT(at(rendered, channel, 0), 0.0) << c.name;
            EXPECT_NEAR(at(predicted, channel, 0) / at(rendered, channel, 0), 1.0, c.tolerance)
                << c.name << " channel " << channel;
            EXPECT_NEAR(at(predicted, channel, 1), 0.0, 1e-9) << c.name;
            EXPECT_LT(at(rendered, channel, 1), 1e-3 * at(rendered, channel, 0)) << c.name;
        }
        EXPECT_NEAR(at(predicted, 2, 0) / at(predicted, 0, 0), 0.25, 1e-5) << c.name;
    }
    // The optically thin formula would give the opaque blob several times its light.
    const Emitters opaque = lampAt(Vec3d(2.0, 0.0, 0.0), 0.4, 0.95, 20.0);
    const double thin = 20.0 * std::pow(2 * M_PI, 1.5) * std::pow(0.4, 3) * (-std::log(1 - 0.95)) /
                        0.25 / (4.0 + 0.16);
    EXPECT_GT(thin, 2.0 * at(renderedAxisIrradiance(opaque, 0.0), 0, 0));
}

TEST(EmitterLight, AnEnvmapsHighlightsLightTheNormalsThatFaceThem) {
    // Columns 3W/4 face +x (docs/conventions.md); an orange patch there, grey elsewhere.
    auto envmap = torch::full({1, 3, 60, 120}, 0.5f);
    auto patch = envmap.narrow(2, 27, 6).narrow(3, 87, 6);
    patch.select(1, 0).fill_(20.0f);
    patch.select(1, 1).fill_(10.0f);
    patch.select(1, 2).fill_(5.0f);
    const auto e = highlightAxisIrradiance(envmap);
    EXPECT_GT(at(e, 0, 0), 0.0);
    EXPECT_NEAR(at(e, 0, 1), 0.0, 1e-9);
    EXPECT_GT(at(e, 0, 0), 10.0 * std::max(at(e, 0, 2), at(e, 0, 3)));
    EXPECT_NEAR(at(e, 2, 0) / at(e, 0, 0), 0.25, 1e-5);  // in the patch's colour, grey left out
    // A highlight the photo saw is left to the MPI.
    auto observed = torch::zeros({1, 1, 60, 120});
    observed.narrow(2, 27, 6).narrow(3, 87, 6).fill_(1.0f);
    EXPECT_NEAR(highlightAxisIrradiance(envmap, observed).abs().max().item<double>(), 0.0, 1e-12);
    // Grey alone has no highlight.
    EXPECT_NEAR(
        highlightAxisIrradiance(torch::full({1, 3, 60, 120}, 0.9f)).abs().max().item<double>(), 0.0,
        1e-12);
}

TEST(EmitterLight, TheLossAsksForTheHighlightsLight) {
    auto envmap = torch::full({1, 3, 60, 120}, 0.5f);
    envmap.narrow(2, 27, 6).narrow(3, 87, 6).fill_(10.0f);
    const Vec3d origin(0.0, 0.0, 0.0);
    const auto lossWithRadiance = [&](double radiance, const torch::Tensor& light,
                                      torch::Tensor* gradient) {
        Emitters e = lampAt(Vec3d(2.0, 0.0, 0.0), 0.3, 0.3, radiance);
        e.radiance.requires_grad_(true);
        const auto loss = emitterLightLoss(e, kLayout, 0.03, {origin}, {light});
        if (gradient) {
            loss.backward();
            *gradient = e.radiance.grad().sum();
        }
        return loss.item<double>();
    };
    // The lamp faces the highlight: a dark one is asked for light; the radiance that matches the
    // highlight on +x scores best, and brighter or darker scores worse.
    torch::Tensor gradient;
    const double dark = lossWithRadiance(0.01, envmap, &gradient);
    EXPECT_LT(gradient.item<double>(), 0.0);
    const Emitters unit = lampAt(Vec3d(2.0, 0.0, 0.0), 0.3, 0.3, 1.0);
    const double perUnit =
        at(emitterAxisIrradiance(unit, emitterIntensity(unit, kLayout, 0.03), origin), 0, 0);
    const double matched = at(highlightAxisIrradiance(envmap), 0, 0) / perUnit;
    const double best = lossWithRadiance(matched, envmap, nullptr);
    EXPECT_LT(best, dark);
    EXPECT_LT(best, lossWithRadiance(10.0 * matched, envmap, nullptr));
    EXPECT_LT(best, lossWithRadiance(0.1 * matched, envmap, nullptr));
    // Without a highlight, a bright lamp is asked to dim.
    const auto grey = torch::full({1, 3, 60, 120}, 0.5f);
    const double bright = lossWithRadiance(matched, grey, &gradient);
    EXPECT_GT(bright, 0.0);
    EXPECT_GT(gradient.item<double>(), 0.0);
    EXPECT_LT(lossWithRadiance(0.01, grey, nullptr), bright);
    // Overshooting costs more than falling as far short: four times too bright against four
    // times too dim.
    EXPECT_GT(lossWithRadiance(4.0 * matched, envmap, nullptr),
              lossWithRadiance(0.25 * matched, envmap, nullptr));
    // Under a red highlight, a white lamp is asked for more red and less blue, through its
    // radiance and opacity; its place (the cell loss's to teach) and size (the envmap losses')
    // get no gradient here.
    auto red = torch::full({1, 3, 60, 120}, 0.5f);
    red.narrow(2, 27, 6).narrow(3, 87, 6).select(1, 0).fill_(30.0f);
    Emitters white = lampAt(Vec3d(2.0, 0.0, 0.0), 0.3, 0.3, matched);
    for (torch::Tensor* t : {&white.radiance, &white.alpha, &white.position, &white.radius})
        t->requires_grad_(true);
    emitterLightLoss(white, kLayout, 0.03, {origin}, {red}).backward();
    EXPECT_LT(white.radiance.grad()[0][0].item<double>(), 0.0);
    EXPECT_GT(white.radiance.grad()[0][2].item<double>(), 0.0);
    EXPECT_NE(white.alpha.grad()[0].item<double>(), 0.0);
    for (const torch::Tensor* t : {&white.position, &white.radius})
        EXPECT_FALSE(t->grad().defined() && t->grad().abs().sum().item<double>() > 0.0);
}

}  // namespace
}  // namespace lh::net
