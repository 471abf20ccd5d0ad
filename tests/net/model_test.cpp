// The networks as a whole: shapes and ranges of every stage, gradients from the envmap loss
// into the MPI network, a few optimisation steps that lower the loss, and model files.
#include "net/lighthouse_net.h"
#include "net/losses.h"
#include "net/mpi_render.h"
#include "net/tensor_image.h"
#include "net/volume_render.h"
#include "net/weight_average.h"
#include "net/widen.h"
#include "tests/net/net_test_scenes.h"

#include "tests/support/temp_path.h"

#include <gtest/gtest.h>

#include <map>

#include "core/errors.h"

#include <filesystem>
#include <fstream>

namespace lh::net {
namespace {

using test::planeCamera;
using test::renderPlane;
using test::tinyConfig;

PairInputs tinyPair(const NetConfig& config) {
    const PinholeCamera ref = planeCamera(64, 32), src = planeCamera(64, 32, Vec3d(0.2, 0.0, 0.0));
    return makePairInputs(renderPlane(ref, 2.0), renderPlane(src, 2.0), ref, src, 1.0, 4.0, config,
                          torch::Device(torch::kCPU));
}

bool allIn(const torch::Tensor& t, double lo, double hi) {
    return torch::isfinite(t).all().item<bool>() && t.min().item<double>() >= lo &&
           t.max().item<double>() <= hi;
}

TEST(Model, EveryStageHasItsShapeAndRange) {
    torch::manual_seed(0);
    const NetConfig config = tinyConfig();
    LighthouseNet net(config);
    const PairInputs in = tinyPair(config);
    EXPECT_EQ(in.refEncoded.sizes(), (std::vector<int64_t>{1, 3, 16, 32}));
    EXPECT_EQ(in.depths.size(), 16u);
    EXPECT_GT(in.depths.front(), in.depths.back());  // far to near
    const PipelineOutput out = net->run(in);
    EXPECT_EQ(out.mpi.sizes(), (std::vector<int64_t>{1, 4, 16, 16, 32}));
    EXPECT_TRUE(allIn(out.mpi, 0, 1));
    ASSERT_EQ(out.cubes.size(), 2u);
    for (int k = 0; k < 2; ++k) {
        EXPECT_EQ(out.mpiCubes[size_t(k)].sizes(), (std::vector<int64_t>{1, 4, 16, 16, 16}));
        EXPECT_EQ(out.cubes[size_t(k)].sizes(), (std::vector<int64_t>{1, 4, 16, 16, 16}));
        EXPECT_TRUE(allIn(out.mpiCubes[size_t(k)], 0, 1));
        EXPECT_TRUE(allIn(out.cubes[size_t(k)], 0, 1));
    }
    const auto env = renderEnvmapTorch(out.cubes, in.layout, Vec3d(0, 0, 1), 16, 8, 32);
    EXPECT_EQ(env.sizes(), (std::vector<int64_t>{1, 3, 8, 16}));
    EXPECT_TRUE(allIn(env, 0, 1));
    const auto view = renderMpiView(out.mpi, in.depths, in.ref, in.ref);
    EXPECT_EQ(view.sizes(), (std::vector<int64_t>{1, 3, 16, 32}));
    EXPECT_TRUE(allIn(view, 0, 1));
}

TEST(Model, CropOfTheCoarserLevelCoversTheFinerLevel) {
    // Level 1 covers x, y in the middle half and z in the front half of level 0; level 2 the
    // back half in z of level 1.
    auto coarse = torch::zeros({1, 1, 8, 8, 8});
    coarse[0][0][4][2][2] = 1.0;  // z = 4 (front half), y = 2, x = 2: the crop's first voxel
    const auto up0 = cropCoarserLevel(coarse, 0);
    EXPECT_EQ(up0.sizes(), (std::vector<int64_t>{1, 1, 8, 8, 8}));
    EXPECT_EQ(up0.sum().item<double>(), 8.0);  // one voxel -> a 2x2x2 block
    EXPECT_EQ(up0[0][0][1][1][1].item<double>(), 1.0);
    auto coarse1 = torch::zeros({1, 1, 8, 8, 8});
    coarse1[0][0][3][5][5] = 1.0;  // back half in z for levels >= 1
    const auto up1 = cropCoarserLevel(coarse1, 1);
    EXPECT_EQ(up1[0][0][7][7][7].item<double>(), 1.0);
}

TEST(Model, EnvmapLossReachesTheMpiNetwork) {
    torch::manual_seed(1);
    const NetConfig config = tinyConfig();
    LighthouseNet net(config);
    const PairInputs in = tinyPair(config);
    const PipelineOutput out = net->run(in);
    const auto env = renderEnvmapTorch(out.cubes, in.layout, Vec3d(0.1, 0, 1.5), 16, 8, 32);
    imageLoss(env, torch::full_like(env, 0.3)).backward();
    double mpiGradient = 0;
    for (const auto& p : net->mpiNet->parameters())
        if (p.grad().defined()) mpiGradient += p.grad().abs().sum().item<double>();
    EXPECT_GT(mpiGradient, 0.0);
    double completionGradient = 0;
    for (const auto& p : net->completion[0]->parameters())
        if (p.grad().defined()) completionGradient += p.grad().abs().sum().item<double>();
    EXPECT_GT(completionGradient, 0.0);
}

TEST(Model, FewStepsOnATinySceneLowerTheLoss) {
    torch::manual_seed(2);
    const NetConfig config = tinyConfig();
    LighthouseNet net(config);
    const PairInputs in = tinyPair(config);
    const PinholeCamera tgtFull = planeCamera(64, 32, Vec3d(-0.1, 0.05, 0.1));
    const PinholeCamera tgt = tgtFull.resized(config.width, config.height);
    const auto tgtImage = imageToTensor(renderPlane(tgt, 2.0));
    const auto envTarget = torch::full({1, 3, 8, 16}, 0.25);
    torch::optim::Adam optimizer(net->parameters(), torch::optim::AdamOptions(2e-3));
    const auto loss = [&] {
        const PipelineOutput out = net->run(in);
        return imageLoss(renderMpiView(out.mpi, in.depths, in.ref, tgt), tgtImage) +
               imageLoss(renderEnvmapTorch(out.cubes, in.layout, Vec3d(0, 0, 1), 16, 8, 32),
                         envTarget);
    };
    const double first = loss().item<double>();
    for (int step = 0; step < 25; ++step) {
        optimizer.zero_grad();
        auto l = loss();
        l.backward();
        zeroNonFiniteGradients(net->parameters());
        optimizer.step();
    }
    const double last = loss().item<double>();
    EXPECT_LT(last, 0.8 * first) << "first " << first << " last " << last;
}

// With the colour anchor, a completion network that outputs zeros (no knowledge) paints empty
// space in the photo's mean colour, and an exposure change of the photo scales it alike.
TEST(Model, ColourAnchorPaintsInventedColoursInThePhotosMeanColour) {
    torch::manual_seed(0);
    const NetConfig config = test::tinyHdrConfig();
    ASSERT_TRUE(config.colourAnchor);
    LighthouseNet net(config);
    {
        torch::NoGradGuard noGrad;
        for (auto& completion : net->completion) {
            completion->head->conv->weight.zero_();
            completion->head->conv->bias.zero_();
        }
    }
    for (const double exposure : {1.0, 3.0}) {
        PairInputs in = tinyPair(config);
        in.refLinear = in.refLinear * exposure;
        const auto mean = in.refLinear.mean({2, 3}).reshape({3});  // the photo's mean linear colour
        const PipelineOutput out = net->run(in);
        for (size_t k = 0; k < out.cubes.size(); ++k) {
            // Voxels the MPI left empty: the output is 0.5 x (anchor colour, alpha 0.5).
            const auto empty = (out.mpiCubes[k].sum(1) == 0).squeeze(0);  // [R, R, R]
            ASSERT_GT(empty.sum().item<int64_t>(), 100) << "level " << k;
            for (int c = 0; c < 3; ++c) {
                const auto invented = out.cubes[k][0][c].masked_select(empty) * 2.0;
                EXPECT_NEAR(invented.mean().item<double>(), mean[c].item<double>(),
                            0.01 * mean[c].item<double>())
                    << "level " << k << " channel " << c << " exposure " << exposure;
                EXPECT_LT((invented.max() - invented.min()).item<double>(), 1e-4 * exposure);
            }
        }
    }
    NetConfig withoutAnchor = config;
    withoutAnchor.colourAnchor = false;
    EXPECT_TRUE(
        config.sameParameters(withoutAnchor));  // train --init fine-tunes one into the other
    withoutAnchor.baseWidth = 8;
    EXPECT_FALSE(config.sameParameters(withoutAnchor));
    EXPECT_TRUE(NetConfig::fromJson(config.toJson(), "test").colourAnchor);
    // Models written before the anchor existed have no key, and load without one.
    std::string legacy = config.toJson();
    const std::string key = "\"colour_anchor\":true,";
    ASSERT_NE(legacy.find(key), std::string::npos) << legacy;
    legacy.erase(legacy.find(key), key.size());
    EXPECT_FALSE(NetConfig::fromJson(legacy, "test").colourAnchor);
}

TEST(Model, ThePruningThresholdTravelsWithTheModelAndShapesNoParameter) {
    NetConfig pruned = tinyConfig();
    pruned.pruneAlpha = 0.2;
    EXPECT_TRUE(pruned.sameParameters(tinyConfig()));  // train --init fine-tunes across it
    EXPECT_DOUBLE_EQ(NetConfig::fromJson(pruned.toJson(), "test").pruneAlpha, 0.2);
    torch::manual_seed(3);
    LighthouseNet net(pruned);
    const std::string path = test::uniqueTempPath("lighthouse_model_prune_test.pt");
    saveModel(net, path, true);
    EXPECT_DOUBLE_EQ(loadModel(path, torch::Device(torch::kCPU))->config.pruneAlpha, 0.2);
    std::filesystem::remove(path);
    // Models written before the key existed were trained unpruned.
    std::string legacy = pruned.toJson();
    const std::string key = ",\"prune_alpha\":0.2";
    ASSERT_NE(legacy.find(key), std::string::npos) << legacy;
    legacy.erase(legacy.find(key), key.size());
    EXPECT_EQ(NetConfig::fromJson(legacy, "test").pruneAlpha, 0.0);
    pruned.pruneAlpha = 1.0;
    EXPECT_THROW(pruned.validate(), InputError);
}

TEST(Model, TheHighlightGainTravelsWithTheModelAndShapesNoParameter) {
    NetConfig gained = tinyConfig();
    gained.highlightGain = 10.0;
    EXPECT_TRUE(gained.sameParameters(tinyConfig()));  // train --init fine-tunes across it
    torch::manual_seed(3);
    LighthouseNet net(gained);
    const std::string path = test::uniqueTempPath("lighthouse_model_gain_test.pt");
    saveModel(net, path, true);
    EXPECT_DOUBLE_EQ(loadModel(path, torch::Device(torch::kCPU))->config.highlightGain, 10.0);
    std::filesystem::remove(path);
    // Models written before the key existed were trained without a gain.
    std::string legacy = gained.toJson();
    const std::string key = ",\"highlight_gain\":10.0";
    ASSERT_NE(legacy.find(key), std::string::npos) << legacy;
    legacy.erase(legacy.find(key), key.size());
    EXPECT_EQ(NetConfig::fromJson(legacy, "test").highlightGain, 1.0);
    for (double bad : {0.5, kMaxHighlightGain + 1}) {
        gained.highlightGain = bad;
        EXPECT_THROW(gained.validate(), InputError) << bad;
    }
}

TEST(Model, SavedAndLoadedModelGivesIdenticalOutputs) {
    torch::manual_seed(3);
    LighthouseNet net(tinyConfig());
    net->eval();
    const std::string path = test::uniqueTempPath("lighthouse_model_test.pt");
    saveModel(net, path);
    LighthouseNet loaded = loadModel(path, torch::Device(torch::kCPU));
    EXPECT_EQ(loaded->config.toJson(), tinyConfig().toJson());
    const PairInputs in = tinyPair(net->config);
    torch::NoGradGuard noGrad;
    const PipelineOutput a = net->run(in), b = loaded->run(in);
    EXPECT_TRUE(torch::equal(a.mpi, b.mpi));
    for (size_t k = 0; k < a.cubes.size(); ++k) EXPECT_TRUE(torch::equal(a.cubes[k], b.cubes[k]));
    std::filesystem::remove(path);
}

TEST(Model, WideSharesTheStandardMpiNetworkAndNothingElse) {
    const NetConfig standard = NetConfig::standard(), wide = NetConfig::byName("wide");
    wide.validate();
    EXPECT_EQ(wide.baseWidth, 2 * standard.baseWidth);
    EXPECT_FALSE(wide.sameParameters(standard));
    // Tiny stand-ins of the two (same relation: only the completion width differs), so the
    // test builds in milliseconds: what matches is exactly the MPI network.
    NetConfig narrow = test::tinyHdrConfig(), wider = narrow;
    wider.baseWidth = 2 * narrow.baseWidth;
    torch::manual_seed(8);
    LighthouseNet from(narrow), to(wider);
    std::map<std::string, torch::Tensor> before;
    for (const auto& p : to->named_parameters()) before[p.key()] = p.value().clone();
    const MatchedWeights m = copyMatchingWeights(to, from);
    EXPECT_GT(m.copied, 0);
    EXPECT_LT(m.copied, m.tensors);
    EXPECT_LT(m.copiedValues, m.values);
    // Each tensor is the source's where name and shape match, and untouched elsewhere.
    const auto fromParameters = from->named_parameters();
    int mpiTensors = 0, kept = 0;
    for (const auto& p : to->named_parameters()) {
        const torch::Tensor* source = fromParameters.find(p.key());
        const bool matches = source && source->sizes().equals(p.value().sizes());
        if (p.key().rfind("mpi_net", 0) == 0) {
            ++mpiTensors;
            EXPECT_TRUE(matches) << p.key();
        }
        if (matches) {
            EXPECT_TRUE(torch::equal(p.value(), *source)) << p.key();
        } else {
            ++kept;
            EXPECT_TRUE(torch::equal(p.value(), before[p.key()])) << p.key() << " was overwritten";
        }
    }
    EXPECT_GT(mpiTensors, 0);
    EXPECT_GT(kept, 0);
}

TEST(Model, WideningKeepsThePredictionsAndSplitsEachChannelUnevenly) {
    NetConfig narrowConfig = test::tinyHdrConfig(), wideConfig = narrowConfig;
    wideConfig.baseWidth = 2 * narrowConfig.baseWidth;
    torch::manual_seed(9);
    LighthouseNet narrow(narrowConfig), wide(wideConfig);
    {
        // Away from the initial gains and biases (1 and 0), so that every path is exercised.
        torch::NoGradGuard noGrad;
        for (auto& p : narrow->parameters()) p.add_(0.05 * torch::randn_like(p));
    }
    narrow->eval();
    wide->eval();
    widenModel(wide, narrow);
    const PairInputs in = tinyPair(narrowConfig);
    torch::NoGradGuard noGrad;
    const PipelineOutput a = narrow->run(in), b = wide->run(in);
    ASSERT_EQ(a.cubes.size(), b.cubes.size());
    for (size_t k = 0; k < a.cubes.size(); ++k)
        EXPECT_TRUE(torch::allclose(a.cubes[k], b.cubes[k], 1e-4, 1e-5))
            << "level " << k << ": largest difference "
            << (a.cubes[k] - b.cubes[k]).abs().max().item<double>();
    // The two copies of an input channel get different halves of its weights (they sum to it).
    const auto weight = wide->completion[0]->encRes[0]->first->conv->weight;
    const int64_t half = weight.size(1) / 2;
    const auto first = weight.narrow(1, 0, half), second = weight.narrow(1, half, half);
    EXPECT_FALSE(torch::allclose(first, second));
    const auto narrowWeight = narrow->completion[0]->encRes[0]->first->conv->weight;
    EXPECT_TRUE(torch::allclose((first + second).narrow(0, 0, narrowWeight.size(0)), narrowWeight,
                                1e-5, 1e-6));

    NetConfig otherPlanes = wideConfig;
    otherPlanes.planes = 2 * narrowConfig.planes;
    LighthouseNet unrelated(otherPlanes);
    EXPECT_THROW(widenModel(unrelated, narrow), InputError);
}

TEST(Model, WeightAverageMovesByOneMinusTheDecayPerUpdate) {
    // From 0 towards weights of 1 at decay 0.75: 0.25, then 0.4375 (= 1 - 0.75^2).
    LighthouseNet average(tinyConfig()), current(tinyConfig());
    {
        torch::NoGradGuard noGrad;
        for (auto& p : average->parameters()) p.zero_();
        for (auto& p : current->parameters()) p.fill_(1.0);
    }
    updateWeightAverage(average, current, 0.75);
    for (const auto& p : average->parameters())
        EXPECT_TRUE(torch::allclose(p, torch::full_like(p, 0.25)));
    updateWeightAverage(average, current, 0.75);
    for (const auto& p : average->parameters())
        EXPECT_TRUE(torch::allclose(p, torch::full_like(p, 0.4375)));
    for (const auto& p : average->parameters()) EXPECT_FALSE(p.grad().defined());
}

TEST(Model, EqualWeightsAreEqualFilesWhateverTheirNames) {
    // Data-parallel and sharded runs are checked against single runs byte for byte.
    torch::manual_seed(5);
    LighthouseNet net(tinyConfig());
    const std::string a = test::uniqueTempPath("lighthouse_model_a.pt");
    const std::string b = test::uniqueTempPath("another_name.pt");
    saveModel(net, a);
    saveModel(net, b);
    const auto bytes = [](const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    EXPECT_FALSE(bytes(a).empty());
    EXPECT_EQ(bytes(a), bytes(b));
    std::filesystem::remove(a);
    std::filesystem::remove(b);
}

TEST(Model, HalfPrecisionModelIsHalfTheSizeAndGivesNearlyTheSameOutputs) {
    torch::manual_seed(4);
    LighthouseNet net(test::tinyHdrConfig());
    net->eval();
    const std::string full = test::uniqueTempPath("lighthouse_model_full.pt");
    const std::string half = test::uniqueTempPath("lighthouse_model_half.pt");
    saveModel(net, full);
    saveModel(net, half, /*halfPrecision=*/true);
    EXPECT_LT(std::filesystem::file_size(half), 0.6 * std::filesystem::file_size(full));
    LighthouseNet loaded = loadModel(half, torch::Device(torch::kCPU));
    for (const auto& p : loaded->parameters()) EXPECT_EQ(p.scalar_type(), torch::kFloat32);
    const PairInputs in = tinyPair(net->config);
    torch::NoGradGuard noGrad;
    const PipelineOutput a = net->run(in), b = loaded->run(in);
    EXPECT_LT((a.mpi - b.mpi).abs().max().item<double>(), 2e-2);
    for (size_t k = 0; k < a.cubes.size(); ++k)
        EXPECT_LT(
            ((a.cubes[k] - b.cubes[k]).abs() / (a.cubes[k].abs() + 1e-2)).max().item<double>(),
            5e-2);
    // The network it was saved from still trains in float32.
    for (const auto& p : net->parameters()) EXPECT_EQ(p.scalar_type(), torch::kFloat32);
    std::filesystem::remove(full);
    std::filesystem::remove(half);
}

TEST(Model, NotAModelFileIsAClearError) {
    const std::string path = test::uniqueTempPath("lighthouse_not_a_model.pt");
    { std::ofstream(path) << "hello"; }
    EXPECT_THROW(loadModel(path, torch::Device(torch::kCPU)), FileError);
    EXPECT_THROW(loadModel(path + ".missing", torch::Device(torch::kCPU)), FileError);
    std::filesystem::remove(path);
}

TEST(Losses, SpectralNormBoundsTheLayerGain) {
    torch::manual_seed(4);
    SpectralConv2d conv(3, 8, 1);
    conv->weight.data().mul_(50.0);  // a layer with a large gain
    for (int i = 0; i < 30; ++i) conv->forward(torch::randn({1, 3, 8, 8}));  // power iterations
    const auto matrix = (conv->weight / 1.0).view({8, -1});
    const double sigmaMax =
        std::get<1>(torch::linalg::svd(matrix, false, c10::nullopt))[0].item<double>();
    const auto v = torch::randn({matrix.size(1)});
    conv->eval();
    // The normalised weight's largest singular value is 1.
    const auto normalised = matrix / sigmaMax;
    EXPECT_NEAR(std::get<1>(torch::linalg::svd(normalised, false, c10::nullopt))[0].item<double>(),
                1.0, 1e-4);
    // And the layer's own estimate matches it.
    const auto u = conv->u;
    const auto vv = torch::nn::functional::normalize(
        torch::mv(matrix.t(), u), torch::nn::functional::NormalizeFuncOptions().dim(0));
    EXPECT_NEAR(torch::dot(u, torch::mv(matrix, vv)).item<double>(), sigmaMax, 1e-3 * sigmaMax);
    (void)v;
}

TEST(Losses, HingeLossesHaveTheirKnownValues) {
    EXPECT_NEAR(
        discriminatorHingeLoss(torch::full({4}, 2.0), torch::full({4}, -2.0)).item<double>(), 0.0,
        1e-9);
    EXPECT_NEAR(discriminatorHingeLoss(torch::zeros({4}), torch::zeros({4})).item<double>(), 2.0,
                1e-9);
    EXPECT_NEAR(generatorHingeLoss(torch::full({4}, 0.5)).item<double>(), -0.5, 1e-9);
}

TEST(Losses, NonFiniteGradientsAreZeroed) {
    auto p = torch::ones({3}, torch::requires_grad());
    p.mutable_grad() = torch::tensor({1.0f, std::nanf(""), INFINITY});
    EXPECT_EQ(zeroNonFiniteGradients({p}), 2);
    EXPECT_TRUE(torch::equal(p.grad(), torch::tensor({1.0f, 0.0f, 0.0f})));
}

}  // namespace
}  // namespace lh::net

// --vgg: a TorchScript archive of VGG-19 features weights (random here: the real ones cannot
// be downloaded on this machine) loads, gives zero for identical images and more for
// different ones, and a file that is not one is refused.
#include "net/vgg_loss.h"

#include <torch/script.h>

namespace lh::net {
namespace {

std::string writeVggArchive(const std::string& name, bool complete) {
    torch::jit::Module archive("VggWeights");
    const int widths[16] = {64,  64,  128, 128, 256, 256, 256, 256,
                            512, 512, 512, 512, 512, 512, 512, 512};
    int in = 3;
    for (int c = 0; c < (complete ? 16 : 10); ++c) {
        const std::string stem = std::to_string(VggPerceptualLoss::kConvIndices[c]);
        archive.register_buffer(stem + "_weight",
                                torch::randn({widths[c], in, 3, 3}) * std::sqrt(2.0 / (in * 9)));
        archive.register_buffer(stem + "_bias", torch::zeros({widths[c]}));
        in = widths[c];
    }
    const std::string path = test::uniqueTempPath(name);
    archive.save(path);
    return path;
}

TEST(VggLoss, LoadsTorchScriptWeightsAndMeasuresDifferences) {
    torch::manual_seed(6);
    const std::string path = writeVggArchive("lighthouse_vgg_test.pt", true);
    const VggPerceptualLoss loss(path, torch::Device(torch::kCPU));
    const auto a = torch::rand({1, 3, 32, 64}), b = torch::rand({1, 3, 32, 64});
    EXPECT_NEAR(loss(a, a).item<double>(), 0.0, 1e-7);
    EXPECT_GT(loss(a, b).item<double>(), 0.01);
    auto p = a.clone().requires_grad_(true);
    loss(p, b).backward();
    EXPECT_GT(p.grad().abs().sum().item<double>(), 0.0);
    std::filesystem::remove(path);
}

TEST(VggLoss, IncompleteOrForeignFilesAreRefused) {
    const std::string partial = writeVggArchive("lighthouse_vgg_partial.pt", false);
    EXPECT_THROW(VggPerceptualLoss(partial, torch::Device(torch::kCPU)), FileError);
    std::filesystem::remove(partial);
    const std::string text = test::uniqueTempPath("lighthouse_vgg_text.pt");
    { std::ofstream(text) << "not an archive"; }
    EXPECT_THROW(VggPerceptualLoss(text, torch::Device(torch::kCPU)), FileError);
    EXPECT_THROW(VggPerceptualLoss(text + ".missing", torch::Device(torch::kCPU)), FileError);
    std::filesystem::remove(text);
}

}  // namespace
}  // namespace lh::net
