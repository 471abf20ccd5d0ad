// The HDR design and direct supervision: the HDR activation, the new losses' known values,
// the 2D MPI network's shapes, and short optimisations with known outcomes (an empty room's
// interior becomes empty; a volume moves towards its oracle).
#include "image/metrics.h"
#include "net/hdr.h"
#include "net/lighthouse_net.h"
#include "net/losses.h"
#include "net/tensor_image.h"
#include "net/volume_render.h"
#include "tests/net/net_test_scenes.h"
#include "vdb/mpi.h"

#include <cmath>

#include <gtest/gtest.h>

namespace lh::net {
namespace {

using test::planeCamera;
using test::renderPlane;
using test::tinyHdrConfig;

PairInputs tinyPair(const NetConfig& config, float brightness = 1.f) {
    const PinholeCamera ref = planeCamera(64, 32), src = planeCamera(64, 32, Vec3d(0.2, 0.0, 0.0));
    ImageRGB a = renderPlane(ref, 2.0), b = renderPlane(src, 2.0);
    for (float& v : a.pixels) v = std::min(1.f, v * brightness);
    for (float& v : b.pixels) v = std::min(1.f, v * brightness);
    return makePairInputs(a, b, ref, src, 1.0, 4.0, config, torch::Device(torch::kCPU));
}

TEST(Hdr, ActivationExceedsOneAndStaysFinite) {
    const auto x = torch::tensor({-1e6, -3.0, 0.0, 2.0, 5.0, 1e6, 1e30});
    const auto y = hdrActivation(x);
    EXPECT_TRUE(torch::isfinite(y).all().item<bool>());
    EXPECT_GT(y.min().item<double>(), 0.0);
    EXPECT_NEAR(y[3].item<double>(), std::exp(2.0), 1e-2);  // the soft clamp bends it by 0.1%
    EXPECT_GT(y[4].item<double>(), 100.0);                  // a lamp
    EXPECT_NEAR(y[6].item<double>(), std::exp(kMaxLogRadiance), 1.0);
}

TEST(Hdr, SaturationWeightMarksOnlyClippedPixels) {
    auto image = torch::zeros({1, 3, 1, 3});
    image[0][0][0][0] = 0.5;   // mid grey: not clipped
    image[0][1][0][1] = 0.95;  // half way into the ramp
    image[0][2][0][2] = 1.0;   // clipped
    const auto w = saturationWeight(image);
    EXPECT_NEAR(w[0][0][0][0].item<double>(), 0.0, 1e-6);
    EXPECT_NEAR(w[0][0][0][1].item<double>(), 0.5, 1e-5);
    EXPECT_NEAR(w[0][0][0][2].item<double>(), 1.0, 1e-6);
}

TEST(Losses, HdrImageLossIsZeroOnIdenticalInputsAndSeesBrightness) {
    const auto a = torch::full({1, 3, 4, 8}, 50.0);
    EXPECT_EQ(hdrImageLoss(a, a).item<double>(), 0.0);
    // A lamp of 50 predicted as 1: imageLoss (clamped) cannot see it, the HDR loss can.
    const auto dim = torch::full_like(a, 1.0);
    EXPECT_NEAR(imageLoss(dim, a).item<double>(), 0.0, 1e-6);
    EXPECT_NEAR(hdrImageLoss(dim, a).item<double>(), std::log(51.0) - std::log(2.0), 1e-5);
}

// A lamp spread over its 4x4 block with its power kept costs nothing at block 4, and what the
// full-resolution loss charges for the spread; moved to another block, it costs again.
TEST(Losses, CoarseHdrLossSeesEachBlocksLightHoweverItIsSpread) {
    auto room = torch::full({1, 3, 8, 16}, 0.2);
    EXPECT_EQ(coarseHdrImageLoss(room, room, 4).item<double>(), 0.0);
    auto lamp = room.clone(), spread = room.clone(), moved = room.clone();
    lamp.narrow(2, 1, 1).narrow(3, 5, 1).fill_(0.2 + 160.0);           // one pixel of block (0, 1)
    spread.narrow(2, 0, 4).narrow(3, 4, 4).fill_(0.2 + 160.0 / 16.0);  // its power over the block
    moved.narrow(2, 1, 1).narrow(3, 9, 1).fill_(0.2 + 160.0);          // one pixel of block (0, 2)
    EXPECT_NEAR(coarseHdrImageLoss(spread, lamp, 4).item<double>(), 0.0, 1e-6);
    EXPECT_GT(hdrImageLoss(spread, lamp).item<double>(), 0.2);  // 0.28
    // Two of the 8 blocks differ by ln(1 + 10.2) - ln(1.2), on every channel.
    const double expected = 2.0 / 8.0 * (std::log(11.2) - std::log(1.2));
    EXPECT_NEAR(coarseHdrImageLoss(moved, lamp, 4).item<double>(), expected, 1e-5);
    EXPECT_NEAR(coarseHdrImageLoss(moved, lamp, 1).item<double>(),
                hdrImageLoss(moved, lamp).item<double>(), 1e-7);
    // Moved 3 pixels, into the next 4x4 block but the same 8x8 one: larger blocks forgive it.
    auto nearby = room.clone();
    nearby.narrow(2, 1, 1).narrow(3, 2, 1).fill_(0.2 + 160.0);
    EXPECT_GT(coarseHdrImageLoss(nearby, lamp, 4).item<double>(), 0.1);
    EXPECT_NEAR(coarseHdrImageLoss(nearby, lamp, 8).item<double>(), 0.0, 1e-6);
    // A block larger than the image is cut to its 8 rows: the two 8x8 blocks, each a mean of
    // 0.2 + 160 / 64 = 2.7 where the other has 0.2.
    EXPECT_NEAR(coarseHdrImageLoss(moved, lamp, 40).item<double>(), std::log(3.7 / 1.2), 1e-5);
}

TEST(Losses, HighlightLossAsksForTheObservedLampsAndNoOthers) {
    // Two pixels: a lamp of 30 the photo saw, and a wall of 0.5.
    auto truth = torch::full({1, 3, 1, 2}, 0.5);
    truth.narrow(3, 0, 1).fill_(30.0);
    const auto seen = torch::ones({1, 1, 1, 2});
    EXPECT_EQ(highlightLoss(truth, truth, seen).item<double>(), 0.0);
    // The lamp at 2 is enough (min(30, 2)); at 1 it is short by ln 3 - ln 2, over 2 pixels.
    auto dim = truth.clone();
    dim.narrow(3, 0, 1).fill_(2.0);
    EXPECT_NEAR(highlightLoss(dim, truth, seen).item<double>(), 0.0, 1e-6);
    dim.narrow(3, 0, 1).fill_(1.0);
    EXPECT_NEAR(highlightLoss(dim, truth, seen).item<double>(), (std::log(3.0) - std::log(2.0)) / 2,
                1e-5);
    // Not asked for where the photo did not see it.
    const auto unseen = torch::tensor({0.f, 1.f}).view({1, 1, 1, 2});
    EXPECT_NEAR(highlightLoss(dim, truth, unseen).item<double>(), 0.0, 1e-6);
    // A wall shown as a highlight (luminance 3) costs ln 4 - ln 2; up to 1 it costs nothing.
    auto glare = truth.clone();
    glare.narrow(3, 1, 1).fill_(3.0);
    EXPECT_NEAR(highlightLoss(glare, truth, seen).item<double>(),
                (std::log(4.0) - std::log(2.0)) / 2, 1e-5);
    glare.narrow(3, 1, 1).fill_(1.0);
    EXPECT_NEAR(highlightLoss(glare, truth, seen).item<double>(), 0.0, 1e-6);
}

TEST(Losses, LogRadianceEncodingTellsALampFromAWhiteWall) {
    const auto radiance = torch::tensor({0.0, 1.0, 100.0, 1000.0, -1.0});
    const auto seen = logRadianceEncode(radiance);
    EXPECT_NEAR(seen[0].item<double>(), 0.0, 1e-7);
    EXPECT_NEAR(seen[1].item<double>(), std::log(2.0) / std::log(101.0), 1e-6);
    EXPECT_NEAR(seen[2].item<double>(), 1.0, 1e-6);
    EXPECT_NEAR(seen[3].item<double>(), std::log(1001.0) / std::log(101.0), 1e-6);
    EXPECT_NEAR(seen[4].item<double>(), 0.0, 1e-7) << "negative radiance is black";
    // Clamped sRGB sees a white wall (1) and a lamp (100) alike.
    const auto srgb = srgbEncodeTensor(radiance);
    EXPECT_NEAR(srgb[1].item<double>(), srgb[2].item<double>(), 1e-6);
}

TEST(Losses, SquaredImageLossIsWhatPsnrScores) {
    // Zero on identical images, 1 between black and white (clamped: a lamp of 50 is white),
    // and on any pair 10^(-PSNR / 10) of image/metrics.h's PSNR.
    const auto black = torch::zeros({1, 3, 4, 8});
    EXPECT_EQ(squaredImageLoss(black, black).item<double>(), 0.0);
    EXPECT_NEAR(squaredImageLoss(black, torch::full_like(black, 50.0)).item<double>(), 1.0, 1e-6);
    ImageRGB a(16, 8), b(16, 8);
    for (int r = 0; r < 8; ++r)
        for (int c = 0; c < 16; ++c)
            for (int ch = 0; ch < 3; ++ch) {
                a.at(c, r)[ch] = 0.05f * float((c + 2 * r + ch) % 11);
                b.at(c, r)[ch] = 0.04f * float((3 * c + r) % 13) + (c == 5 ? 20.0f : 0.0f);
            }
    const double loss =
        squaredImageLoss(imageToTensor(a).to(torch::kFloat64), imageToTensor(b).to(torch::kFloat64))
            .item<double>();
    // To 1e-5 relative: the loss's sRGB curve keeps its derivative finite at 0 by an offset of
    // 1e-6 inside the power.
    EXPECT_NEAR(loss, std::pow(10.0, -psnr(a, b) / 10.0), 1e-5 * loss);
}

TEST(Losses, AxisIrradianceOfAConstantEnvmapIsPiTimesItsRadiance) {
    // A uniform sky of radiance L gives E = pi L on every side; a sky lit only from above
    // (rows of the top half, -y) gives pi L to the normal facing up (-y) and none to +y.
    const auto uniform = torch::full({1, 3, 60, 120}, 2.0);
    const auto e = axisIrradianceTensor(uniform);
    ASSERT_EQ(e.sizes(), torch::IntArrayRef({1, 3, 6}));
    EXPECT_NEAR(e.min().item<double>(), 2.0 * M_PI, 2e-3 * 2.0 * M_PI);
    EXPECT_NEAR(e.max().item<double>(), 2.0 * M_PI, 2e-3 * 2.0 * M_PI);
    auto upper = torch::zeros({1, 3, 60, 120});
    upper.narrow(2, 0, 30).fill_(1.0);
    const auto u = axisIrradianceTensor(upper);
    EXPECT_NEAR(u[0][1][3].item<double>(), M_PI, 2e-3 * M_PI);      // normal -y: up
    EXPECT_NEAR(u[0][1][2].item<double>(), 0.0, 1e-6);              // normal +y: down
    EXPECT_NEAR(u[0][1][0].item<double>(), M_PI / 2, 2e-3 * M_PI);  // sideways: half the sky
}

TEST(Losses, AxisIrradianceTensorEqualsTheMetric) {
    // The loss integrates with the metric's own weights: a lamp at +x and a blue floor give the
    // same six irradiances in torch as image/metrics.h's axisIrradiance.
    ImageRGB envmap(48, 24);
    for (int r = 0; r < envmap.height; ++r)
        for (int c = 0; c < envmap.width; ++c) {
            float* p = envmap.at(c, r);
            p[0] = 0.2f + 0.01f * float(c);
            p[1] = 0.3f;
            p[2] = r >= envmap.height / 2 ? 0.8f : 0.1f;
        }
    envmap.at(3 * envmap.width / 4, envmap.height / 2)[0] = 90.0f;
    const AxisIrradiance expected = axisIrradiance(envmap);
    const auto e = axisIrradianceTensor(imageToTensor(envmap).to(torch::kFloat64));
    for (int n = 0; n < kAxisNormals; ++n)
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(e[0][ch][n].item<double>(), expected.rgb[n][ch], 1e-9 * expected.rgb[n][ch])
                << "normal " << n << " channel " << ch;
}

TEST(Losses, IrradianceLossIsZeroOnIdenticalInputsAndIndifferentToWhereALampIs) {
    auto room = torch::full({1, 3, 30, 60}, 0.2);
    EXPECT_EQ(irradianceLoss(room, room).item<double>(), 0.0);
    // A lamp in the ceiling, and the same lamp moved a few pixels along the ceiling: the
    // per-pixel losses see two errors, the irradiance from every side barely changes.
    auto lamp = room.clone(), moved = room.clone();
    lamp.narrow(2, 2, 2).narrow(3, 10, 2).fill_(500.0);
    moved.narrow(2, 2, 2).narrow(3, 13, 2).fill_(500.0);
    const double shifted = irradianceLoss(moved, lamp).item<double>();
    const double missing = irradianceLoss(room, lamp).item<double>();
    EXPECT_GT(missing, 0.3);
    EXPECT_LT(shifted, 0.3 * missing);  // 0.08 against 0.37
    EXPECT_GT(hdrImageLoss(moved, lamp).item<double>(),
              0.5 * hdrImageLoss(room, lamp).item<double>());
}

TEST(Losses, FocusedIrradianceLossKeepsTheValueAndSendsTheGradientToBrightPixels) {
    // A dim room with one brighter patch (a predicted lamp), against a truth holding more light.
    auto room = torch::full({1, 3, 30, 60}, 0.1, torch::kFloat64);
    room.narrow(2, 2, 2).narrow(3, 10, 2).fill_(4.0);
    const auto truth = torch::full({1, 3, 30, 60}, 0.5, torch::kFloat64);
    const auto gradientOf = [&](double focus) {
        auto x = room.clone().requires_grad_(true);
        const auto loss = focusedIrradianceLoss(x, truth, focus);
        loss.backward();
        return std::make_pair(loss.item<double>(), x.grad());
    };
    const auto [plainValue, plain] = gradientOf(0.0);
    const auto [focusedValue, focused] = gradientOf(1.0);
    EXPECT_DOUBLE_EQ(plainValue, irradianceLoss(room, truth).item<double>());
    EXPECT_NEAR(focusedValue, plainValue, 1e-12);
    // Mirror columns of one row (theta and -theta): the same solid angle and the same sum of
    // cosines over the six normals, so the plain loss asks both pixels for the same light (every
    // normal receives too little), the focused one asks the lamp for 40 (4.0 / 0.1) times as much.
    const auto lampPixel = [](const torch::Tensor& g) { return g[0][0][2][10].item<double>(); };
    const auto dimPixel = [](const torch::Tensor& g) { return g[0][0][2][49].item<double>(); };
    EXPECT_NEAR(lampPixel(plain) / dimPixel(plain), 1.0, 1e-9);
    EXPECT_NEAR(lampPixel(focused) / dimPixel(focused), 40.0, 1e-6);
    EXPECT_LT(lampPixel(focused), 0.0);  // more light lowers the loss
}

TEST(Losses, VoxelLossIsMinimalOnIdenticalCubesAndKnownOtherwise) {
    auto cube = torch::zeros({1, 4, 16, 16, 16});
    cube.narrow(1, 3, 1).narrow(2, 0, 8).fill_(1.0);  // the far half is opaque
    cube.narrow(1, 0, 3).fill_(2.0);
    // Identical: only the tenth of the cross-entropy of alpha clamped to [1e-4, 1 - 1e-4] is
    // left, -ln(1 - 1e-4) for the empty and the opaque voxels alike.
    const double floor = -0.1 * std::log1p(-1e-4);
    EXPECT_NEAR(voxelLoss({cube}, {cube}).item<double>(), floor, 1e-6);
    // Everything empty instead: on the opaque half (weight 3, against weight 1 for the empty
    // half) alpha costs 1 + 0.1 (-ln 1e-4) and colour ln(1 + 2) - ln(1 + 0).
    const auto empty = torch::zeros_like(cube);
    const double expected =
        (3.0 * (1.0 - 0.1 * std::log(1e-4) + std::log(3.0)) + 1.0 * floor) / (3.0 + 1.0);
    EXPECT_NEAR(voxelLoss({empty}, {cube}).item<double>(), expected, 1e-4);
}

TEST(Losses, VoxelLossPrefersEmptyOverFogWhereAWallIsUnlikely) {
    // A voxel opaque in one example of ten: the loss summed over the ten is lower for an
    // empty prediction than for fog at the mean (alpha 0.1), so uncertainty does not make fog.
    const auto cubeWith = [](double alpha) {
        auto c = torch::zeros({1, 4, 16, 16, 16});
        c.narrow(1, 3, 1).fill_(alpha);
        return c;
    };
    const auto total = [&](double predicted) {
        return 1.0 * voxelLoss({cubeWith(predicted)}, {cubeWith(1.0)}).item<double>() +
               9.0 * voxelLoss({cubeWith(predicted)}, {cubeWith(0.0)}).item<double>();
    };
    EXPECT_LT(total(0.0), total(0.1));
    EXPECT_LT(total(0.01), total(0.3));
}

// An MPI whose only opaque plane is plane `index`.
torch::Tensor singlePlaneMpi(int planes, int index) {
    auto mpi = torch::zeros({1, 4, planes, 8, 8});
    mpi.narrow(1, 3, 1).narrow(2, index, 1).fill_(1.0);
    return mpi;
}

TEST(Losses, MpiDepthLossIsZeroAtTheTrueDepthAndGrowsAwayFromIt) {
    const std::vector<double> depths = disparityLinearDepths(1.0, 4.0, 16);
    const auto truth = torch::full({1, 1, 8, 8}, depths[5]);
    EXPECT_NEAR(mpiDepthLoss(singlePlaneMpi(16, 5), depths, truth).item<double>(), 0.0, 1e-5);
    const double near = mpiDepthLoss(singlePlaneMpi(16, 6), depths, truth).item<double>();
    const double far = mpiDepthLoss(singlePlaneMpi(16, 12), depths, truth).item<double>();
    EXPECT_NEAR(near, 1.0 / 15.0, 1e-4);  // one plane of 15 steps
    EXPECT_NEAR(far, 7.0 / 15.0, 1e-4);
    // A transparent MPI puts everything on the far plane.
    EXPECT_NEAR(
        mpiExpectedDisparity(torch::zeros({1, 4, 16, 8, 8}), depths)[0][0][0][0].item<double>(),
        0.25, 1e-6);
}

TEST(Losses, BinaryAlphaLossIsZeroForEmptyAndOpaqueVoxelsAndPeaksAtHalf) {
    auto cube = torch::zeros({1, 4, 8, 8, 8});
    cube.narrow(1, 3, 1).narrow(2, 0, 4).fill_(1.0);  // half opaque, half empty
    EXPECT_NEAR(binaryAlphaLoss({cube}).item<double>(), 0.0, 1e-7);
    auto fog = torch::zeros({1, 4, 8, 8, 8});
    fog.narrow(1, 3, 1).fill_(0.5);
    EXPECT_NEAR(binaryAlphaLoss({cube, fog}).item<double>(), 0.125, 1e-6);
    // Its gradient lowers alpha below one half and raises it above.
    auto alpha = torch::tensor({0.2f, 0.8f}).view({1, 1, 1, 1, 2});
    auto voxels = torch::cat({torch::zeros({1, 3, 1, 1, 2}), alpha}, 1).requires_grad_(true);
    binaryAlphaLoss({voxels}).backward();
    const auto g = voxels.grad().narrow(1, 3, 1).flatten();
    EXPECT_GT(g[0].item<double>(), 0.0);  // descent lowers 0.2
    EXPECT_LT(g[1].item<double>(), 0.0);  // and raises 0.8
}

TEST(Losses, SparsityLossIsTheMeanAlpha) {
    auto cube = torch::zeros({1, 4, 16, 16, 16});
    cube.narrow(1, 3, 1).narrow(2, 0, 4).fill_(1.0);
    EXPECT_NEAR(sparsityLoss({cube, torch::zeros_like(cube)}).item<double>(), 0.125, 1e-6);
}

TEST(HdrModel, TwoDimensionalMpiNetworkGivesEveryStageItsShape) {
    torch::manual_seed(0);
    const NetConfig config = tinyHdrConfig();
    LighthouseNet net(config);
    ASSERT_TRUE(net->mpiNet2d);
    const PairInputs in = tinyPair(config, 4.f);  // mostly clipped
    const PipelineOutput out = net->run(in);
    EXPECT_EQ(out.mpi.sizes(), (std::vector<int64_t>{1, 4, 16, 16, 32}));
    EXPECT_TRUE(torch::isfinite(out.mpi).all().item<bool>());
    EXPECT_GE(out.mpi.min().item<double>(), 0.0);
    ASSERT_EQ(out.cubes.size(), 2u);
    for (const auto& c : out.cubes) {
        EXPECT_EQ(c.sizes(), (std::vector<int64_t>{1, 4, 32, 32, 32}));
        EXPECT_TRUE(torch::isfinite(c).all().item<bool>());
        EXPECT_LE(c.narrow(1, 3, 1).max().item<double>(), 1.0);
    }
}

constexpr int kSteps = 60;  // Adam steps of the short optimisations below

// Cubes of an empty room seen from inside: every level opaque and emissive (radiance 2) in
// its outer voxel shell where that shell is the room's wall (level 0 only), empty inside.
std::vector<torch::Tensor> emptyRoomCubes(int levels, int r) {
    std::vector<torch::Tensor> cubes;
    for (int k = 0; k < levels; ++k) {
        auto c = torch::zeros({1, 4, r, r, r});
        if (k == 0) {
            auto shell = torch::ones({1, 1, r, r, r});
            shell.narrow(2, 2, r - 4).narrow(3, 2, r - 4).narrow(4, 2, r - 4).fill_(0.0);
            c.narrow(1, 3, 1).copy_(shell);
            c.narrow(1, 0, 3).copy_(shell.expand({1, 3, r, r, r}) * 2.0);
        }
        cubes.push_back(c);
    }
    return cubes;
}

double interiorAlpha(const torch::Tensor& cube) {
    const int64_t r = cube.size(2);
    return cube.narrow(1, 3, 1)
        .narrow(2, 4, r - 8)
        .narrow(3, 4, r - 8)
        .narrow(4, 4, r - 8)
        .mean()
        .item<double>();
}

TEST(DirectSupervision, AnEmptyRoomPredictsEmptySpaceInsideAfterBriefTraining) {
    torch::manual_seed(7);
    const NetConfig config = tinyHdrConfig();
    LighthouseNet net(config);
    const PairInputs in = tinyPair(config);
    const auto target = emptyRoomCubes(config.levels, config.resolution);
    torch::optim::Adam optimizer(net->parameters(), torch::optim::AdamOptions(1e-2));
    double before = 0;
    for (int step = 0; step < kSteps; ++step) {
        const PipelineOutput out = net->run(in);
        if (step == 0) before = interiorAlpha(out.cubes[1]) + interiorAlpha(out.cubes[0]);
        auto loss = voxelLoss(out.cubes, target);
        optimizer.zero_grad();
        loss.backward();
        optimizer.step();
    }
    torch::NoGradGuard noGrad;
    const PipelineOutput out = net->run(in);
    for (const auto& c : out.cubes) EXPECT_LT(interiorAlpha(c), 0.05);
    EXPECT_LT(interiorAlpha(out.cubes[0]) + interiorAlpha(out.cubes[1]), 0.2 * before);
    // And the walls it has learnt light the room: an envmap from the middle is bright (about
    // the walls' radiance 2, well above what a sigmoid could give).
    const auto env = renderEnvmapTorch(out.cubes, in.layout, Vec3d(0.0, 0.0, 0.5), 16, 8, 32);
    EXPECT_GT(env.mean().item<double>(), 1.2);
}

TEST(DirectSupervision, DrivesTheVolumeTowardsItsOracle) {
    torch::manual_seed(8);
    const NetConfig config = tinyHdrConfig();
    LighthouseNet net(config);
    const PairInputs in = tinyPair(config);
    // An oracle with a bright block (radiance 6) in the middle of each level.
    std::vector<torch::Tensor> oracle;
    for (int k = 0; k < config.levels; ++k) {
        auto c = torch::zeros({1, 4, 32, 32, 32});
        c.narrow(2, 12, 8).narrow(3, 12, 8).narrow(4, 12, 8).fill_(6.0);
        c.narrow(1, 3, 1).narrow(2, 12, 8).narrow(3, 12, 8).narrow(4, 12, 8).fill_(1.0);
        oracle.push_back(c);
    }
    torch::optim::Adam optimizer(net->parameters(), torch::optim::AdamOptions(1e-2));
    double first = 0, last = 0;
    for (int step = 0; step < 3 * kSteps / 2; ++step) {
        auto loss = voxelLoss(net->run(in).cubes, oracle);
        (step == 0 ? first : last) = loss.item<double>();
        optimizer.zero_grad();
        loss.backward();
        optimizer.step();
    }
    EXPECT_LT(last, 0.4 * first) << "first " << first << " last " << last;
    torch::NoGradGuard noGrad;
    const auto cube = net->run(in).cubes[0];
    // The block's centre is opaque and brighter than 1; the corners are empty.
    EXPECT_GT(cube[0][3][16][16][16].item<double>(), 0.5);
    EXPECT_GT(cube[0][0][16][16][16].item<double>(), 1.5);
    EXPECT_LT(cube[0][3][2][2][2].item<double>(), 0.2);
}

}  // namespace
}  // namespace lh::net
