// Pretraining of a "+cells" emitter head's photo classifier: the cells a scene's lamps fall in
// (known values, mirrored, clamped, level 0's side capped at 40 m), which of them a photo does
// not show, a classifier that learns which side of the photo is lit tells the held-out photos'
// lamps apart where the training distribution cannot, keeping its best held-out epoch, and it
// leaves the rest of the head alone.
#include "net/lamp_cell_pretraining.h"

#include "core/errors.h"
#include "net/config.h"

#include "tests/support/test_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace lh::net {
namespace {

TEST(LampCellTarget, EachLampPutsItsShareOnTheCellItFallsIn) {
    // far 4 m: level 0 spans [-4, 4]^3 m, cells of 1 m. (0.5, -2.5, 3.2) lies in cell x 4,
    // y 1, z 7: index (7 x 8 + 1) x 8 + 4 = 460; mirrored, x 3: 459.
    const auto one = torch::tensor({0.5f, -2.5f, 3.2f}).reshape({1, 3});
    const auto t = lampCellTarget(one, 4.0, 8);
    ASSERT_EQ(t.numel(), 512);
    EXPECT_EQ(t[460].item<float>(), 1.0f);
    EXPECT_EQ(t.sum().item<float>(), 1.0f);
    EXPECT_EQ(lampCellTarget(one, 4.0, 8, /*mirrored=*/true)[459].item<float>(), 1.0f);
    // Two lamps: half each; one far outside falls to the nearest cell (x 7).
    const auto two = torch::tensor({0.5f, -2.5f, 3.2f, 100.f, -2.5f, 3.2f}).reshape({2, 3});
    const auto t2 = lampCellTarget(two, 4.0, 8);
    EXPECT_FLOAT_EQ(t2[460].item<float>(), 0.5f);
    EXPECT_FLOAT_EQ(t2[7 * 64 + 8 + 7].item<float>(), 0.5f);
    // Level 0 is at most 40 m wide: at far 30 the cells are 5 m, and (4, 0, 0) is in x 4.
    const auto far = lampCellTarget(torch::tensor({4.f, 0.f, 0.f}).reshape({1, 3}), 30.0, 8);
    EXPECT_EQ(far[(4 * 8 + 4) * 8 + 4].item<float>(), 1.0f);
    EXPECT_THROW(lampCellTarget(torch::zeros({0, 3}), 4.0, 8), InputError);
}

TEST(LampsOutsideView, KeepsTheLampsThePhotoDoesNotShow) {
    // A 100x80 camera of focal 50 px at the origin looking down +z: (0, 0, 2) projects to its
    // centre, (3, 0, 2) to x = 125 (outside), (0, 0, -2) lies behind it, and (0.9, 0, 1) to
    // x = 95 (inside, near the right edge).
    PinholeCamera camera = test::centredCamera(100, 80, 50.0);
    const auto lamps = torch::tensor({0.f, 0.f, 2.f, 3.f, 0.f, 2.f, 0.f, 0.f, -2.f, 0.9f, 0.f, 1.f})
                           .reshape({4, 3});
    const auto outside = lampsOutsideView(lamps, camera);
    ASSERT_TRUE(outside.defined());
    ASSERT_EQ(outside.size(0), 2);
    EXPECT_TRUE(torch::equal(outside[0], lamps[1]));
    EXPECT_TRUE(torch::equal(outside[1], lamps[2]));
    // Turned half a turn about y, the camera sees the lamp behind it and not the others.
    camera.rotation = Mat3d(-1, 0, 0, 0, 1, 0, 0, 0, -1);
    const auto turned = lampsOutsideView(lamps, camera);
    ASSERT_EQ(turned.size(0), 3);
    EXPECT_TRUE(torch::equal(turned[2], lamps[3]));
    // Every lamp shown: nothing left; no lamps: nothing.
    EXPECT_FALSE(lampsOutsideView(lamps.narrow(0, 2, 1), camera).defined());
    EXPECT_FALSE(lampsOutsideView(torch::Tensor(), camera).defined());
}

// A photo lit on its left or right half; the lamp is in cell x 1 or (mirrored) x 6, y 0, z 4.
LampCellExample sidedExample(bool left, double brightness) {
    LampCellExample e;
    e.photo = torch::full({1, 3, 32, 48}, 0.05 * brightness);
    e.photo.narrow(3, left ? 0 : 24, 24).fill_(0.8 * brightness);
    const auto lamp = torch::tensor({left ? -2.5f : 2.5f, -3.5f, 0.5f}).reshape({1, 3});
    e.cells = lampCellTarget(lamp, 4.0, 8);
    e.mirroredCells = lampCellTarget(lamp, 4.0, 8, /*mirrored=*/true);
    return e;
}

TEST(PretrainLampCells, TheClassifierLearnsWhichSideThePhotoIsLitFrom) {
    torch::manual_seed(4);
    EmitterHead head(3, true, true);
    std::vector<LampCellExample> training, heldOut;
    for (int i = 0; i < 16; ++i) training.push_back(sidedExample(i % 2 == 0, 0.5 + 0.1 * i));
    for (int i = 0; i < 4; ++i) heldOut.push_back(sidedExample(i % 2 == 1, 0.7 + 0.3 * i));
    // Not pretrained: the classifier says nothing (logits 0, the head as without it).
    EXPECT_EQ(head->photoCellLogits(heldOut[0].photo).abs().max().item<float>(), 0.0f);
    const auto whereBefore = head->where->weight.clone();
    LampCellPretraining options;
    options.epochs = 40;
    options.batch = 4;
    options.learningRate = 3e-3;
    std::ostringstream log;
    const LampCellScores scores = pretrainLampCells(head, training, heldOut, options, log);
    // The training distribution is half on each cell (mirrors included): ln 2 from each photo's.
    const auto half = 0.5 * (training[0].cells + training[1].cells);
    const LampCellScores blind = scoreLampCells(0.999 * half + 0.001 / 512, heldOut);
    EXPECT_NEAR(blind.divergence, std::log(2.0), 0.01);
    EXPECT_LT(scores.divergence, 0.15) << log.str();
    EXPECT_EQ(scores.peakHit, 1.0) << log.str();
    EXPECT_NEAR(scoreLampCells(head, heldOut).divergence, scores.divergence, 1e-9);
    EXPECT_TRUE(torch::equal(head->where->weight, whereBefore));  // the rest of the head
    EXPECT_NE(log.str().find("16 photos (and their mirror images), 4 held out"), std::string::npos)
        << log.str();
    EXPECT_NE(log.str().find("lamp cells, epoch 40/40"), std::string::npos) << log.str();
    EXPECT_NE(log.str().find("lamp cells: kept epoch "), std::string::npos) << log.str();
}

TEST(PretrainLampCells, ACellsHeadIsNamedBySuffixAndNeedsThePhoto) {
    const NetConfig c = NetConfig::byName("wide+emitters+photo+cells");
    EXPECT_TRUE(c.emitterPhotoCells);
    EXPECT_TRUE(c.emitterPhoto);
    EXPECT_FALSE(c.sameParameters(NetConfig::byName("wide+emitters+photo")));
    EXPECT_TRUE(NetConfig::fromJson(c.toJson(), "test").emitterPhotoCells);
    EXPECT_FALSE(NetConfig::byName("wide+emitters+photo").emitterPhotoCells);
    EXPECT_THROW(NetConfig::byName("wide+emitters+cells"), InputError);
}

}  // namespace
}  // namespace lh::net
