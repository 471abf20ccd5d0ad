// The emitter head: its blobs' known values in the cubes (opacity, colour, mixing with what a
// voxel already holds, widening on coarse levels), a gradient that moves a lamp to where the
// loss wants light, the "+emitters" configurations, and a model fine-tuned from one without it;
// the lamp-cell loss's known values, and a "+photo" head that reads the photo and, trained on
// that loss alone, puts its lamps on the true one; and a "+apart" head, whose lamps take
// different peaks.
#include "net/emitter_head.h"
#include "net/lamp_cell_pretraining.h"
#include "net/lighthouse_net.h"
#include "net/losses.h"
#include "tests/net/net_test_scenes.h"

#include "core/errors.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>

namespace lh::net {
namespace {

// Level 0 spans [-4, 4]^3 m in 16^3 voxels of 0.5 m: voxel (z, y, x) is centred at
// -3.75 + 0.5 (x, y, z).
const VolumeLayout kLayout{8.0, 2, 16};

torch::Tensor voxelCentreOfLevel0(int64_t z, int64_t y, int64_t x) {
    return torch::tensor({-3.75 + 0.5 * x, -3.75 + 0.5 * y, -3.75 + 0.5 * z}, torch::kFloat32);
}

Emitters oneEmitter(const torch::Tensor& position, double radius, double alpha,
                    std::vector<float> rgb) {
    Emitters e;
    e.position = position.reshape({1, 3});
    e.radius = torch::tensor({float(radius)});
    e.alpha = torch::tensor({float(alpha)});
    e.radiance = torch::tensor(rgb).reshape({1, 3});
    return e;
}

std::vector<torch::Tensor> emptyCubes() {
    return {torch::zeros({1, 4, 16, 16, 16}), torch::zeros({1, 4, 16, 16, 16})};
}

TEST(AddEmitters, ABlobHoldsItsColourAndAGaussianOpacity) {
    // Radius 1 m (2 voxels): the voxel two steps along x lies one standard deviation away.
    const auto e = oneEmitter(voxelCentreOfLevel0(9, 8, 10), 1.0, 0.5, {4.0f, 2.0f, 1.0f});
    const auto cubes = addEmitters(emptyCubes(), e, kLayout);
    const auto voxel = [&](int64_t z, int64_t y, int64_t x) {
        return cubes[0][0].select(1, z).select(1, y).select(1, x);  // [4]
    };
    EXPECT_NEAR(voxel(9, 8, 10)[3].item<double>(), 0.5, 1e-5);
    EXPECT_NEAR(voxel(9, 8, 12)[3].item<double>(), 0.5 * std::exp(-0.5), 1e-5);
    EXPECT_NEAR(voxel(9, 8, 10 - 2)[3].item<double>(), 0.5 * std::exp(-0.5), 1e-5);
    // Empty voxels take the emitter's colour wherever it reaches.
    for (int64_t x : {10, 12, 14}) {
        EXPECT_NEAR(voxel(9, 8, x)[0].item<double>(), 4.0, 1e-4) << "x " << x;
        EXPECT_NEAR(voxel(9, 8, x)[2].item<double>(), 1.0, 1e-4) << "x " << x;
    }
    // 5 m away, five standard deviations: exp(-12.5) of it.
    EXPECT_NEAR(voxel(9, 8, 0)[3].item<double>(), 0.5 * std::exp(-12.5),
                0.02 * 0.5 * std::exp(-12.5));
}

TEST(AddEmitters, ColoursMixByOpticalDepthWithWhatTheVoxelHolds) {
    auto cubes = emptyCubes();
    // A blue voxel of opacity 0.5 where an orange emitter of opacity 0.5 is centred: equal
    // optical depths ln 2, so the colours average and the opacity is 1 - 0.5 * 0.5.
    cubes[0][0].select(1, 9).select(1, 8).select(1, 10).copy_(torch::tensor({0.f, 0.f, 1.f, 0.5f}));
    const auto e = oneEmitter(voxelCentreOfLevel0(9, 8, 10), 0.5, 0.5, {4.0f, 2.0f, 1.0f});
    const auto out = addEmitters(cubes, e, kLayout)[0][0].select(1, 9).select(1, 8).select(1, 10);
    EXPECT_NEAR(out[0].item<double>(), 2.0, 1e-4);
    EXPECT_NEAR(out[1].item<double>(), 1.0, 1e-4);
    EXPECT_NEAR(out[2].item<double>(), 1.0, 1e-4);
    EXPECT_NEAR(out[3].item<double>(), 0.75, 1e-5);
}

TEST(AddEmitters, AnEmitterOfZeroOpacityLeavesTheCubesAsTheyAre) {
    torch::manual_seed(3);
    std::vector<torch::Tensor> cubes;
    for (int k = 0; k < 2; ++k)
        cubes.push_back(torch::cat(
            {4.0 * torch::rand({1, 3, 16, 16, 16}), 0.99 * torch::rand({1, 1, 16, 16, 16})}, 1));
    const auto e = oneEmitter(voxelCentreOfLevel0(9, 8, 10), 1.0, 0.0, {4.0f, 2.0f, 1.0f});
    const auto out = addEmitters(cubes, e, kLayout);
    for (int k = 0; k < 2; ++k)
        EXPECT_TRUE(torch::allclose(out[k], cubes[k], 1e-4, 1e-5)) << "level " << k;
}

TEST(AddEmitters, ABulbSmallerThanAVoxelIsWidenedWithItsLightKept) {
    // A 5 cm bulb on level 0 (0.5 m voxels) is drawn 0.35 m wide, (0.05 / 0.35)^2 as bright.
    const auto e = oneEmitter(voxelCentreOfLevel0(9, 8, 10), 0.05, 0.5, {49.0f, 49.0f, 49.0f});
    const auto centre =
        addEmitters(emptyCubes(), e, kLayout)[0][0].select(1, 9).select(1, 8).select(1, 10);
    const double widening = std::pow(0.05 / (kMinEmitterWidthVoxels * 0.5), 2);
    EXPECT_NEAR(centre[0].item<double>(), 49.0 * widening, 1e-3);
    EXPECT_NEAR(centre[3].item<double>(), 0.5, 1e-5);
}

TEST(AddEmitters, TheGradientMovesALampToWhereTheLossWantsLight) {
    // Ask for opacity in one voxel; start the lamp 0.6 m beside it: gradient steps on its
    // position alone bring it there.
    const auto target = voxelCentreOfLevel0(9, 8, 10);
    auto position = (target + torch::tensor({0.6f, -0.3f, 0.2f})).requires_grad_(true);
    torch::optim::SGD sgd({position}, torch::optim::SGDOptions(0.5));
    for (int step = 0; step < 200; ++step) {
        Emitters e = oneEmitter(position, 0.5, 0.9, {1.0f, 1.0f, 1.0f});
        const auto cubes = addEmitters(emptyCubes(), e, kLayout);
        const auto loss = -cubes[0][0][3][9][8][10];
        sgd.zero_grad();
        loss.backward();
        sgd.step();
    }
    EXPECT_LT((position.detach() - target).norm().item<double>(), 0.05);
}

TEST(EmitterPositionLoss, TheMeanSquaredDistanceToTheNearestTrueLamp) {
    // The first lamp is 1 m from its nearest true one, the second sits on one: (1 + 0) / 2.
    const auto lamps = torch::tensor({0.f, 0.f, 0.f, 1.f, 0.f, 0.f}).reshape({2, 3});
    const auto truth = torch::tensor({0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 5.f, 5.f, 5.f}).reshape({3, 3});
    EXPECT_NEAR(emitterPositionLoss(lamps, truth).item<double>(), 0.5, 1e-6);
    EXPECT_EQ(emitterPositionLoss(truth, truth).item<double>(), 0.0);
}

TEST(EmitterCellLoss, TheDivergenceFromTheTrueLampsCells) {
    // Four cells; the true lamps are in cells 0 and 2: t = (1/2, 0, 1/2, 0).
    const auto truth = torch::tensor({0.5f, 0.f, 0.5f, 0.f});
    // Two lamps, each sure of one of the true cells: the mixture is t, the divergence 0.
    const auto sure = torch::tensor({60.f, 0.f, 0.f, 0.f, 0.f, 0.f, 60.f, 0.f}).reshape({2, 4});
    EXPECT_NEAR(emitterCellLoss(sure, truth).item<double>(), 0.0, 1e-6);
    // Uniform: p = 1/4 everywhere, KL = 2 x 1/2 ln((1/2) / (1/4)) = ln 2.
    EXPECT_NEAR(emitterCellLoss(torch::zeros({2, 4}), truth).item<double>(), std::log(2.0), 1e-6);
    // Both lamps sure of cell 0: half of t has p ~ e^-60, a divergence of about 30.
    const auto oneSided = torch::tensor({60.f, 0.f, 0.f, 0.f, 60.f, 0.f, 0.f, 0.f}).reshape({2, 4});
    EXPECT_GT(emitterCellLoss(oneSided, truth).item<double>(), 25.0);
    // All the truth in one cell: KL = ln 4 when uniform.
    EXPECT_NEAR(
        emitterCellLoss(torch::zeros({2, 4}), torch::tensor({1.f, 0.f, 0.f, 0.f})).item<double>(),
        std::log(4.0), 1e-6);
    // The divergence of each row, as the pretraining scores it.
    const auto rows =
        cellDivergence(torch::tensor({0.5f, 0.f, 0.5f, 0.f, 1.f, 0.f, 0.f, 0.f}).reshape({2, 4}),
                       torch::full({2, 4}, std::log(0.25f)));
    EXPECT_TRUE(torch::allclose(rows, torch::tensor({std::log(2.f), std::log(4.f)})));
    // A cell the truth leaves empty adds nothing even where p is 0 (ln p = -inf), and its
    // gradient stays finite.
    const auto masked =
        torch::tensor({0.f, -std::numeric_limits<float>::infinity()}, torch::requires_grad());
    const auto divergence =
        cellDivergence(torch::tensor({1.f, 0.f}).reshape({1, 2}), masked.reshape({1, 2}));
    EXPECT_NEAR(divergence.item<double>(), 0.0, 1e-7);
    divergence.sum().backward();
    EXPECT_TRUE(torch::isfinite(masked.grad()).all().item<bool>());
}

TEST(EmitterHead, APhotoHeadIsNamedBySuffixAndNeedsTheEmitters) {
    const NetConfig photo = NetConfig::byName("wide+emitters+photo");
    EXPECT_TRUE(photo.emitterPhoto);
    EXPECT_EQ(photo.emitters, kSuffixEmitters);
    EXPECT_TRUE(NetConfig::byName("wide+photo+emitters").emitterPhoto);
    EXPECT_FALSE(NetConfig::byName("wide+emitters").emitterPhoto);
    EXPECT_FALSE(photo.sameParameters(NetConfig::byName("wide+emitters")));  // the encoder
    EXPECT_TRUE(NetConfig::fromJson(photo.toJson(), "test").emitterPhoto);
    EXPECT_THROW(NetConfig::byName("wide+photo"), InputError);  // no head to read the photo
    auto old = nlohmann::json::parse(NetConfig::byName("wide+emitters").toJson());
    old.erase("emitter_photo");
    EXPECT_FALSE(NetConfig::fromJson(old.dump(), "test").emitterPhoto);
}

TEST(EmitterHead, APhotoHeadTrainedOnTheCellLossPutsItsLampsOnTheTrueOne) {
    // Level 0 of 16^3 voxels over [-4, 4]^3 m: 8^3 cells of 1 m. One true lamp at the centre of
    // cell (x 6, y 1, z 5), far from the middle where an untrained head puts its lamps.
    torch::manual_seed(3);
    EmitterHead head(3, true);
    const auto level0 = torch::rand({1, 4, 16, 16, 16});
    const auto photo = torch::rand({1, 3, 32, 48});
    const auto luminance = torch::tensor(0.5f);
    const auto lamp = torch::tensor({2.5f, -2.5f, 1.5f}).reshape({1, 3});
    const auto cells = lampCellTarget(lamp, kLayout.s0 / 2, kEmitterCellsPerSide);
    Emitters start = head(level0, kLayout, luminance, photo);
    ASSERT_EQ(start.cellLogits.sizes(), torch::IntArrayRef({3, 512}));
    EXPECT_GT((start.position - lamp).norm(2, 1).min().item<double>(), 2.5);
    // The photo reaches the cells: another photo, other logits.
    const Emitters other = head(level0, kLayout, luminance, torch::rand({1, 3, 32, 48}));
    EXPECT_GT((other.cellLogits - start.cellLogits).abs().max().item<double>(), 1e-6);
    // At a rate of 1e-2 Adam overshoots once the loss is near 0 (0.3 nats at step 60 on one
    // machine, 1e-7 at step 40); at 3e-3 it falls smoothly, to 1e-5 by step 60.
    torch::optim::Adam adam(head->parameters(), torch::optim::AdamOptions(3e-3));
    for (int step = 0; step < 60; ++step) {
        const Emitters e = head(level0, kLayout, luminance, photo);
        const auto loss = emitterCellLoss(e.cellLogits, cells);
        adam.zero_grad();
        loss.backward();
        adam.step();
    }
    const Emitters trained = head(level0, kLayout, luminance, photo);
    EXPECT_LT(emitterCellLoss(trained.cellLogits, cells).item<double>(), 0.1);
    // Every lamp at the peak, within half a cell of the true one.
    EXPECT_LT((trained.position - lamp).norm(2, 1).max().item<double>(), 0.5);
}

// Cell index of (z, y, x) in a cube of 8 cells per side.
int64_t cellIndex(int64_t z, int64_t y, int64_t x) { return (z * 8 + y) * 8 + x; }

TEST(EmitterHead, ApartLampsTakeTheBestPeaksThatAreNotNextToAnEarlierOne) {
    // Three lamps sharing one set of logits: the best cell, its neighbour (second best), and
    // two far cells.
    auto logits = torch::zeros({512});
    logits[cellIndex(2, 2, 2)] = 10.0;
    logits[cellIndex(3, 3, 3)] = 9.0;  // a diagonal neighbour: taken by the first lamp
    logits[cellIndex(6, 6, 6)] = 8.0;
    logits[cellIndex(0, 7, 0)] = 7.0;
    const auto shared = logits.unsqueeze(0).repeat({3, 1});
    const auto weights = apartPeakWeights(shared, 8);
    ASSERT_EQ(weights.sizes(), torch::IntArrayRef({3, 512}));
    EXPECT_TRUE(torch::allclose(weights.sum(1), torch::ones({3})));
    EXPECT_EQ(weights[0].argmax().item<int64_t>(), cellIndex(2, 2, 2));
    EXPECT_EQ(weights[1].argmax().item<int64_t>(), cellIndex(6, 6, 6));
    EXPECT_EQ(weights[2].argmax().item<int64_t>(), cellIndex(0, 7, 0));
    // Nothing of the later lamps on the first one's 27 cells.
    EXPECT_EQ(weights[1][cellIndex(3, 3, 3)].item<float>(), 0.0f);
    EXPECT_EQ(weights[2][cellIndex(1, 1, 1)].item<float>(), 0.0f);
    // Without "+apart" all three sit at the one peak.
    EXPECT_EQ(torch::softmax(shared, 1).argmax(1).eq(cellIndex(2, 2, 2)).sum().item<int64_t>(), 3);
    // A cube of 2 cells per side is all one lamp's neighbourhood: the next may use it again.
    const auto tiny = torch::tensor({0.f, 1.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f}).repeat({2, 1});
    EXPECT_TRUE(torch::allclose(apartPeakWeights(tiny, 2), torch::softmax(tiny, 1)));
    // The weights pass the gradient to each lamp's own logits.
    auto trainable = shared.clone().requires_grad_(true);
    apartPeakWeights(trainable, 8)[1][cellIndex(0, 7, 0)].backward();
    EXPECT_GT(trainable.grad()[1][cellIndex(0, 7, 0)].item<float>(), 0.0f);
    EXPECT_EQ(trainable.grad()[0].abs().sum().item<float>(), 0.0f);
}

TEST(EmitterHead, AnApartHeadsLampsAreCellsApartWhereAPlainOnesCoincide) {
    // A "+cells" classifier that has learnt one strong peak (its last layer's bias) and lamps of
    // their own that say nothing (zero position weights): a plain head puts all three there.
    torch::manual_seed(5);
    EmitterHead plain(3, true, true), apart(3, true, true, true);
    for (EmitterHead* head : {&plain, &apart}) {
        torch::NoGradGuard noGrad;
        (*head)->where->weight.zero_();
        auto bias = (*head)->photoCellsOutput()->bias;
        bias.zero_();
        bias[cellIndex(6, 1, 5)] = 5.0;
        bias[cellIndex(1, 6, 2)] = 4.0;
        bias[cellIndex(6, 6, 6)] = 3.0;
        (*head)->eval();
    }
    const auto level0 = torch::rand({1, 4, 16, 16, 16});
    const auto photo = torch::rand({1, 3, 32, 48});
    const auto luminance = torch::tensor(0.5f);
    const Emitters together = plain(level0, kLayout, luminance, photo);
    const Emitters spread = apart(level0, kLayout, luminance, photo);
    const auto pairwise = [](const torch::Tensor& p) {
        return (p.unsqueeze(0) - p.unsqueeze(1)).norm(2, 2) + 100 * torch::eye(p.size(0));
    };
    EXPECT_LT(pairwise(together.position).min().item<double>(), 0.1);
    EXPECT_GT(pairwise(spread.position).min().item<double>(), 2.0);  // the peaks are 4+ m apart
    // The first lamp is at the best peak either way: cell (z 6, y 1, x 5) is centred at
    // (1.5, -2.5, 2.5) m.
    const auto best = torch::tensor({1.5f, -2.5f, 2.5f});
    EXPECT_LT((spread.position[0] - best).norm().item<double>(), 0.2);
    EXPECT_LT((together.position[0] - best).norm().item<double>(), 0.2);
    // The loss reads the same distribution: "+apart" changes only where the lamps go.
    EXPECT_TRUE(torch::allclose(together.cellLogits, spread.cellLogits));
}

TEST(EmitterHead, ApartIsNamedBySuffixNeedsThePhotoAndKeepsTheParameters) {
    const NetConfig apart = NetConfig::byName("wide+emitters+photo+cells+apart");
    EXPECT_TRUE(apart.emitterApart);
    EXPECT_FALSE(NetConfig::byName("wide+emitters+photo+cells").emitterApart);
    EXPECT_TRUE(apart.sameParameters(NetConfig::byName("wide+emitters+photo+cells")));
    EXPECT_TRUE(NetConfig::fromJson(apart.toJson(), "test").emitterApart);
    EXPECT_THROW(NetConfig::byName("wide+emitters+apart"), InputError);  // no peaks to keep apart
    auto old = nlohmann::json::parse(NetConfig::byName("wide+emitters+photo").toJson());
    old.erase("emitter_apart");
    EXPECT_FALSE(NetConfig::fromJson(old.dump(), "test").emitterApart);
}

TEST(EmitterHead, ConfigurationsAreNamedBySuffix) {
    const NetConfig wide = NetConfig::byName("wide");
    const NetConfig lamps = NetConfig::byName("wide+emitters");
    EXPECT_EQ(wide.emitters, 0);
    EXPECT_EQ(lamps.emitters, kSuffixEmitters);
    EXPECT_FALSE(lamps.heightProfile);
    EXPECT_EQ(lamps.name, "wide+emitters");
    EXPECT_FALSE(lamps.sameParameters(wide));  // the head's parameters
    for (const char* both : {"wide+profile+emitters", "wide+emitters+profile"}) {
        const NetConfig c = NetConfig::byName(both);
        EXPECT_TRUE(c.heightProfile) << both;
        EXPECT_EQ(c.emitters, kSuffixEmitters) << both;
    }
    EXPECT_EQ(NetConfig::fromJson(lamps.toJson(), "test").emitters, kSuffixEmitters);
    // Models written before the head existed have no key, and load without one.
    auto old = nlohmann::json::parse(wide.toJson());
    old.erase("emitters");
    EXPECT_EQ(NetConfig::fromJson(old.dump(), "test").emitters, 0);
    EXPECT_THROW(NetConfig::byName("wide+emitters+emitters"), InputError);
    EXPECT_THROW(NetConfig::byName("+emitters"), InputError);
    NetConfig ldr = NetConfig::byName("small");
    ldr.emitters = 2;
    EXPECT_THROW(ldr.validate(), InputError);  // emitters need HDR colours
}

TEST(EmitterHead, AFineTunedModelStartsDimAndItsLampsLearnFromTheCubes) {
    NetConfig plainConfig = test::tinyHdrConfig(), lampConfig = plainConfig;
    lampConfig.emitters = 3;
    torch::manual_seed(12);
    LighthouseNet plain(plainConfig), lamps(lampConfig);
    plain->eval();
    lamps->eval();
    const MatchedWeights m = copyMatchingWeights(lamps, plain);
    EXPECT_LT(m.copied, m.tensors);  // the head starts fresh
    const PinholeCamera ref = test::planeCamera(64, 32),
                        src = test::planeCamera(64, 32, Vec3d(0.2, 0.0, 0.0));
    const PairInputs in =
        makePairInputs(test::renderPlane(ref, 2.0), test::renderPlane(src, 2.0), ref, src, 1.0, 4.0,
                       plainConfig, torch::Device(torch::kCPU));
    const PipelineOutput a = plain->run(in), b = lamps->run(in);
    ASSERT_TRUE(b.emitters.alpha.defined());
    EXPECT_FALSE(a.emitters.alpha.defined());
    ASSERT_EQ(b.emitters.position.sizes(), torch::IntArrayRef({3, 3}));
    // Dim at the start: opacity sigmoid(-4) everywhere, inside level 0.
    EXPECT_TRUE(torch::allclose(b.emitters.alpha, torch::full({3}, 1.0 / (1.0 + std::exp(4.0))),
                                1e-3, 1e-4));
    const double half = in.layout.side(0) / 2;
    EXPECT_LT(b.emitters.position.abs().max().item<double>(), half);
    for (size_t k = 0; k < a.cubes.size(); ++k)
        EXPECT_TRUE(torch::isfinite(b.cubes[k]).all().item<bool>()) << "level " << k;
    // A loss on the cubes reaches the head's parameters (position logits and lamp outputs).
    const auto loss = b.cubes[0].narrow(1, 0, 3).mean() + b.cubes[1].narrow(1, 3, 1).mean();
    loss.backward();
    EXPECT_GT(lamps->emitterHead->where->weight.grad().abs().sum().item<double>(), 0.0);
    EXPECT_GT(lamps->emitterHead->what->weight.grad().abs().sum().item<double>(), 0.0);
}

}  // namespace
}  // namespace lh::net
