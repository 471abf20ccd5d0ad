// The photo head that reads the photo before its clip at 1 ("+unclipped"): the pipeline reads
// an EXR photo clipped everywhere but there; the head sees a photo relative to its own mean, so
// the exposure does not matter but the magnitude of its brightest pixels does; and the lamp-cell
// pretraining reads the examples' renders for it.
#include "core/errors.h"
#include "image/image_io.h"
#include "net/config.h"
#include "net/emitter_head.h"
#include "net/lamp_cell_pretraining.h"
#include "net/lighthouse_net.h"
#include "tests/net/net_test_scenes.h"
#include "tests/net/tiny_training_set.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

namespace lh::net {
namespace {

namespace fs = std::filesystem;

// A tiny HDR model with a "+emitters+photo+cells" head (3 lamps), at an input of 64x32 (the
// photo encoder's size needs multiples of 16).
NetConfig photoHeadConfig(bool unclipped) {
    NetConfig c = test::tinyHdrConfig();
    c.width = 64;
    c.height = 32;
    c.emitters = 3;
    c.emitterPhoto = c.emitterPhotoCells = true;
    c.emitterPhotoUnclipped = unclipped;
    return c;
}

// The plane photo of `camera` with a lamp: a 16x8 block at `lampRadiance` from pixel (8, 4).
ImageRGB photoWithLamp(const PinholeCamera& camera, float lampRadiance) {
    ImageRGB photo = test::renderPlane(camera, 2.0);
    for (int y = 4; y < 12; ++y)
        for (int x = 8; x < 24; ++x) std::fill_n(photo.at(x, y), 3, lampRadiance);
    return photo;
}

TEST(UnclippedPhoto, IsNamedBySuffixNeedsThePhotoAndKeepsTheParameters) {
    const NetConfig c = NetConfig::byName("wide+emitters+photo+cells+apart+unclipped");
    EXPECT_TRUE(c.emitterPhotoUnclipped);
    EXPECT_TRUE(c.emitterApart);
    EXPECT_FALSE(NetConfig::byName("wide+emitters+photo+cells").emitterPhotoUnclipped);
    // The same weights read another photo: a clipped-photo model fine-tunes into one.
    EXPECT_TRUE(c.sameParameters(NetConfig::byName("wide+emitters+photo+cells+apart")));
    EXPECT_TRUE(NetConfig::fromJson(c.toJson(), "test").emitterPhotoUnclipped);
    EXPECT_THROW(NetConfig::byName("wide+emitters+unclipped"), InputError);  // no photo head
    EXPECT_THROW(NetConfig::byName("wide+unclipped"), InputError);
}

TEST(UnclippedPhoto, ThePipelineReadsAnExrPhotoClippedAndKeepsItsRadianceBeside) {
    const NetConfig config = photoHeadConfig(true);
    const PinholeCamera ref = test::planeCamera(64, 32),
                        src = test::planeCamera(64, 32, Vec3d(0.2, 0.0, 0.0));
    ImageRGB exr = photoWithLamp(ref, 40.f);
    exr.at(40, 20)[0] = std::numeric_limits<float>::quiet_NaN();
    exr.at(41, 20)[1] = std::numeric_limits<float>::infinity();
    exr.at(42, 20)[2] = -3.f;
    const PairInputs in = makePairInputs(exr, test::renderPlane(src, 2.0), ref, src, 1.0, 4.0,
                                         config, torch::Device(torch::kCPU));
    EXPECT_LE(in.refLinear.max().item<float>(), 1.f);
    EXPECT_FLOAT_EQ(in.refLinear[0][0][8][16].item<float>(), 1.f);  // inside the lamp: clipped
    EXPECT_FLOAT_EQ(in.refUnclipped[0][0][8][16].item<float>(), 40.f);
    EXPECT_TRUE(torch::isfinite(in.refUnclipped).all().item<bool>());
    EXPECT_FLOAT_EQ(in.refUnclipped[0][0][20][40].item<float>(), 0.f);  // NaN reads as 0
    EXPECT_FLOAT_EQ(in.refUnclipped[0][1][20][41].item<float>(), float(kMaxPhotoRadiance));
    EXPECT_FLOAT_EQ(in.refUnclipped[0][2][20][42].item<float>(), 0.f);
    // Where the photo is below 1 the two agree.
    EXPECT_FLOAT_EQ(in.refUnclipped[0][0][28][4].item<float>(),
                    in.refLinear[0][0][28][4].item<float>());
}

TEST(UnclippedPhoto, OnlyAnUnclippedHeadSeesHowBrightTheClippedLampIs) {
    const PinholeCamera ref = test::planeCamera(64, 32),
                        src = test::planeCamera(64, 32, Vec3d(0.2, 0.0, 0.0));
    const ImageRGB source = test::renderPlane(src, 2.0);
    // Two EXR photos that clip to the same photo: a lamp at 1.5 and one at 60; and that photo,
    // as a PNG would give it.
    const ImageRGB dim = photoWithLamp(ref, 1.5f), bright = photoWithLamp(ref, 60.f),
                   png = photoWithLamp(ref, 1.f);
    torch::Tensor pngLamps[2];  // the lamps' places from the PNG, without and with the suffix
    for (const bool unclipped : {false, true}) {
        const NetConfig config = photoHeadConfig(unclipped);
        torch::manual_seed(21);
        LighthouseNet net(config);
        net->eval();
        torch::NoGradGuard noGrad;
        const auto run = [&](const ImageRGB& photo) {
            return net->run(makePairInputs(photo, source, ref, src, 1.0, 4.0, config,
                                           torch::Device(torch::kCPU)));
        };
        const PipelineOutput a = run(dim), b = run(bright);
        // The MPI and the completion read the clipped photo either way.
        EXPECT_TRUE(torch::equal(a.mpi, b.mpi)) << "unclipped " << unclipped;
        const bool same = torch::allclose(a.emitters.cellLogits, b.emitters.cellLogits);
        EXPECT_EQ(same, !unclipped) << "unclipped " << unclipped;
        pngLamps[unclipped] = run(png).emitters.cellLogits;
    }
    // The same weights with and without the suffix: a PNG gives both the same lamps.
    EXPECT_TRUE(torch::equal(pngLamps[0], pngLamps[1]));
}

TEST(UnclippedPhoto, ThePhotoHeadSeesThePhotoRelativeToItsOwnMean) {
    torch::manual_seed(22);
    EmitterHead head(3, true, true);
    head->eval();
    torch::NoGradGuard noGrad;
    const VolumeLayout layout{8.0, 2, 16};
    const auto level0 = torch::rand({1, 4, 16, 16, 16});
    const auto luminance = torch::tensor(0.5f);
    auto photo = torch::rand({1, 3, 32, 48}) * 0.5;
    photo.narrow(2, 4, 8).narrow(3, 8, 16).fill_(30.0);
    const auto logits = [&](const torch::Tensor& p) {
        return head(level0, layout, luminance, p).cellLogits;
    };
    // Any exposure of the same photo: the same places.
    EXPECT_TRUE(torch::allclose(logits(photo), logits(photo * 8.0), 1e-4, 1e-5));
    // The lamp brighter against the rest: other places.
    EXPECT_FALSE(torch::allclose(logits(photo), logits(photo.clamp_max(1.0)), 1e-4, 1e-5));
}

class UnclippedPretraining : public test::TinyTrainingSetTest {};

TEST_F(UnclippedPretraining, ReadsTheRenderForAnUnclippedHeadAndThePngOtherwise) {
    const fs::path example = fs::path(dataDir()) / "000000";
    // A render of the example's size whose lamp is 50 times white, and one NaN.
    const ImageRGB png = readImage((example / "ref.png").string());
    ImageRGB render(png.width, png.height);
    std::fill(render.pixels.begin(), render.pixels.end(), 0.3f);
    for (int y = 0; y < png.height / 2; ++y)
        for (int x = 0; x < png.width / 2; ++x) std::fill_n(render.at(x, y), 3, 50.f);
    render.at(png.width - 1, png.height - 1)[0] = std::numeric_limits<float>::quiet_NaN();
    writeExr(render, (example / "ref.exr").string());

    bool ok = false;
    const LampCellExample unclipped =
        loadLampCellExample(example.string(), photoHeadConfig(true), ok);
    ASSERT_TRUE(ok) << "the tiny set's first room has no lamp";
    EXPECT_NEAR(unclipped.photo.max().item<float>(), 50.f, 1e-3);
    EXPECT_TRUE(torch::isfinite(unclipped.photo).all().item<bool>());
    EXPECT_EQ(unclipped.photo.sizes(), torch::IntArrayRef({1, 3, 32, 64}));

    const LampCellExample clipped =
        loadLampCellExample(example.string(), photoHeadConfig(false), ok);
    ASSERT_TRUE(ok);
    EXPECT_LE(clipped.photo.max().item<float>(), 1.f);
    // Without the render, the unclipped head reads the PNG as every head does.
    fs::remove(example / "ref.exr");
    const LampCellExample fallback =
        loadLampCellExample(example.string(), photoHeadConfig(true), ok);
    ASSERT_TRUE(ok);
    EXPECT_TRUE(torch::equal(fallback.photo, clipped.photo));
}

}  // namespace
}  // namespace lh::net
