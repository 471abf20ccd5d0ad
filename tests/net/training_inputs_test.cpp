// What training feeds the networks, against known answers: augmentation of photos and HDR
// targets, oracle volumes as dense cubes (at the oracle's resolution and pooled to half), and
// the oneDNN convolutions against libtorch's own.
#include "core/errors.h"
#include "image/image_io.h"
#include "net/augment.h"
#include "net/fast_conv.h"
#include "net/oracle_targets.h"
#include "vdb/lighting_volume.h"
#include "vdb/volume_io.h"

#include "tests/support/temp_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace lh::net {
namespace {

TEST(Augment, PhotosClipAndQuantiseWhileTargetsScale) {
    Augmentation a;
    a.exposure = 2.0;
    a.gain[0] = 1.0, a.gain[1] = 0.5, a.gain[2] = 1.0;
    a.noiseSigma = 0.0;
    ImageRGB photo(1, 1), target(1, 1);
    photo.at(0, 0)[0] = 0.8f;   // x2 -> 1.6: clips at 1
    photo.at(0, 0)[1] = 0.2f;   // x1 -> 0.2: kept, to 8 bits
    photo.at(0, 0)[2] = 0.01f;  // x2 -> 0.02
    target.pixels = {50.f, 50.f, 0.1f};
    Random rng(1);
    augmentPhoto(photo, a, rng);
    augmentRadiance(target, a);
    EXPECT_FLOAT_EQ(photo.at(0, 0)[0], 1.f);
    const float code = std::round(srgbEncode(0.2f) * 255.f) / 255.f;  // an 8-bit value
    EXPECT_FLOAT_EQ(photo.at(0, 0)[1], srgbDecode(code));
    EXPECT_NEAR(photo.at(0, 0)[2], 0.02f, 0.002f);
    EXPECT_FLOAT_EQ(target.at(0, 0)[0], 100.f);  // HDR targets are not clipped
    EXPECT_FLOAT_EQ(target.at(0, 0)[1], 50.f);
    EXPECT_FLOAT_EQ(target.at(0, 0)[2], 0.2f);
}

// Why training exposes the views' unclipped EXRs (net/training_data.h): a lamp of 4 exposed
// 0.6x is 2.4 and clips at 1, as a camera shows it; the same lamp from a PNG, already clipped
// to 1, would become a flat 0.6 whose saturation the network could not see.
TEST(Augment, AnUnclippedLampStaysClippedAtALowerExposure) {
    Augmentation darker;
    darker.exposure = 0.6;
    ImageRGB fromExr(1, 1), fromPng(1, 1);
    fromExr.pixels = {4.f, 4.f, 4.f};
    fromPng.pixels = {1.f, 1.f, 1.f};
    Random rng(2);
    augmentPhoto(fromExr, darker, rng);
    augmentPhoto(fromPng, darker, rng);
    EXPECT_FLOAT_EQ(fromExr.at(0, 0)[0], 1.f);
    EXPECT_NEAR(fromPng.at(0, 0)[0], 0.6f, 0.01f);
}

TEST(Augment, JpegKeepsSmoothContentAndBlursSharpEdges) {
    // A smooth ramp survives JPEG at quality 90 within a few code values; a one-pixel
    // checkerboard of two colours (all high frequency, in the chroma JPEG subsamples below
    // quality 90) is smeared, at 60 more than at 90.
    ImageRGB ramp(64, 48), checker(64, 48);
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) {
                ramp.at(x, y)[c] = srgbDecode(float(x) / 63.f * 0.8f + 0.1f);
                checker.at(x, y)[c] = ((x + y) % 2 == 0) == (c == 0) ? 0.8f : 0.05f;  // red / cyan
            }
    const auto worstCode = [](const ImageRGB& a, const ImageRGB& b) {
        double worst = 0;
        for (std::size_t i = 0; i < a.pixels.size(); ++i)
            worst = std::max(
                worst, std::abs(double(srgbEncode(a.pixels[i]) - srgbEncode(b.pixels[i]))) * 255.0);
        return worst;
    };
    const ImageRGB smooth = jpegRoundTrip(ramp, 90);
    ASSERT_EQ(smooth.width, 64);
    ASSERT_EQ(smooth.height, 48);
    EXPECT_LT(worstCode(smooth, ramp), 6.0);
    const double at90 = worstCode(jpegRoundTrip(checker, 90), checker);
    const double at60 = worstCode(jpegRoundTrip(checker, 60), checker);
    std::printf("JPEG of the checkerboard: worst %.1f code values at quality 90, %.1f at 60\n",
                at90, at60);
    EXPECT_GT(at60, 20.0);
    EXPECT_GT(at60, at90);
    // augmentPhoto applies it when drawn.
    Augmentation a;
    a.jpegQuality = 60;
    ImageRGB photo = checker;
    Random rng(2);
    augmentPhoto(photo, a, rng);
    EXPECT_GT(worstCode(photo, checker), 10.0);
}

TEST(Augment, DrawsWithinItsRangesAndNoiseChangesPixels) {
    Random rng(7);
    int jpegDraws = 0;
    for (int i = 0; i < 200; ++i) {
        const Augmentation a = drawAugmentation(rng);
        EXPECT_GE(a.exposure, std::exp(-0.6) - 1e-12);
        EXPECT_LE(a.exposure, std::exp(0.6) + 1e-12);
        for (double g : a.gain)
            EXPECT_TRUE(g >= std::exp(-0.12) - 1e-12 && g <= std::exp(0.12) + 1e-12);
        EXPECT_TRUE(a.noiseSigma >= 0 && a.noiseSigma <= 2.5 / 255.0);
        EXPECT_TRUE(a.jpegQuality == 0 || (a.jpegQuality >= 60 && a.jpegQuality <= 95))
            << a.jpegQuality;
        jpegDraws += a.jpegQuality > 0;
    }
    EXPECT_GT(jpegDraws, 60);  // about half of 200
    EXPECT_LT(jpegDraws, 140);
    Augmentation noisy;
    noisy.noiseSigma = 2.0 / 255.0;
    ImageRGB flat(32, 32);
    std::fill(flat.pixels.begin(), flat.pixels.end(), 0.2f);
    Random r(3);
    augmentPhoto(flat, noisy, r);
    int changed = 0;
    for (float v : flat.pixels) changed += std::abs(v - 0.2f) > 1e-3f;
    EXPECT_GT(changed, int(flat.pixels.size()) / 4);
}

// A 2-level oracle of 32^3 with one opaque voxel of known colour on level 1.
std::string writeOracle(const VolumeLayout& layout) {
    LightingVolume v = LightingVolume::fromLayout(layout);
    const WorldBox box = layout.box(1);
    const double voxel = layout.voxelSize(1);
    const Vec3d centre = box.min + Vec3d(4.5, 6.5, 8.5) * voxel;  // voxel (x 4, y 6, z 8)
    v.fillLevel(1, [&](const Vec3d& p) -> MediumSample {
        if ((p - centre).length() > 0.1 * voxel) return {};
        return {float(2.0 / voxel), openvdb::Vec3s(3.f, 1.f, 0.5f)};  // optical depth 2
    });
    const std::string path = test::uniqueTempPath("lighthouse_oracle_targets.vdb");
    saveVolume(path, v);
    return path;
}

TEST(OracleTargets, VoxelsBecomeAlphaAndColourAtTheirIndex) {
    const VolumeLayout layout{8.0, 2, 32};
    const std::string path = writeOracle(layout);
    const auto cubes = loadOracleCubes(path, layout, torch::Device(torch::kCPU));
    ASSERT_EQ(cubes.size(), 2u);
    EXPECT_EQ(cubes[1].sizes(), (std::vector<int64_t>{1, 4, 32, 32, 32}));
    EXPECT_NEAR(cubes[1][0][3][8][6][4].item<double>(), 1.0 - std::exp(-2.0),
                1e-5);  // [c, z, y, x]
    EXPECT_NEAR(cubes[1][0][0][8][6][4].item<double>(), 3.0, 1e-5);
    EXPECT_NEAR(cubes[1][0][2][8][6][4].item<double>(), 0.5, 1e-5);
    EXPECT_NEAR(cubes[1].narrow(1, 3, 1).sum().item<double>(), 1.0 - std::exp(-2.0), 1e-5);
    EXPECT_EQ(cubes[0].abs().sum().item<double>(), 0.0);

    // At half the resolution a 2^3 block averages: alpha / 8, the colour kept.
    const auto half = loadOracleCubes(path, VolumeLayout{8.0, 2, 16}, torch::Device(torch::kCPU));
    EXPECT_NEAR(half[1][0][3][4][3][2].item<double>(), (1.0 - std::exp(-2.0)) / 8.0, 1e-6);
    EXPECT_NEAR(half[1][0][0][4][3][2].item<double>(), 3.0, 1e-4);
    std::filesystem::remove(path);
}

TEST(OracleTargets, AnotherLayoutIsAClearError) {
    const std::string path = writeOracle(VolumeLayout{8.0, 2, 32});
    EXPECT_THROW(loadOracleCubes(path, VolumeLayout{10.0, 2, 32}, torch::Device(torch::kCPU)),
                 FileError);
    EXPECT_THROW(loadOracleCubes(path, VolumeLayout{8.0, 3, 32}, torch::Device(torch::kCPU)),
                 FileError);
    EXPECT_THROW(loadOracleCubes(path, VolumeLayout{8.0, 2, 48}, torch::Device(torch::kCPU)),
                 FileError);
    std::filesystem::remove(path);
}

TEST(FastConvolution, AgreesWithLibtorchsConvolutionAndItsGradients) {
    // Batches of 1 and 2, even and odd sizes (an odd size with stride 2 leaves the input's last
    // row out of every window), 2D and 3D: the hand-written gradients of every argument.
    torch::manual_seed(0);
    for (const bool threeD : {false, true})
        for (const int64_t batch : {1, 2})
            for (const int64_t odd : {0, 1}) {
                const auto x = threeD ? torch::randn({batch, 5, 8 + odd, 12, 10 + odd})
                                      : torch::randn({batch, 5, 12 + odd, 10});
                const auto w = threeD ? torch::randn({7, 5, 3, 3, 3}) : torch::randn({7, 5, 3, 3});
                const auto b = torch::randn({7});
                for (const int64_t stride : {1, 2}) {
                    auto xa = x.clone().requires_grad_(true), wa = w.clone().requires_grad_(true);
                    auto xb = x.clone().requires_grad_(true), wb = w.clone().requires_grad_(true);
                    auto ba = b.clone().requires_grad_(true), bb = b.clone().requires_grad_(true);
                    const auto fast = fastConvolution(xa, wa, ba, stride, 1);
                    const auto reference = threeD ? torch::conv3d(xb, wb, bb, stride, 1)
                                                  : torch::conv2d(xb, wb, bb, stride, 1);
                    ASSERT_EQ(fast.sizes(), reference.sizes());
                    EXPECT_LT((fast - reference).abs().max().item<double>(), 1e-4);
                    (fast * fast).sum().backward();
                    (reference * reference).sum().backward();
                    EXPECT_LT((xa.grad() - xb.grad()).abs().max().item<double>(),
                              1e-3 * xb.grad().abs().max().item<double>());
                    EXPECT_LT((wa.grad() - wb.grad()).abs().max().item<double>(),
                              1e-4 * wb.grad().abs().max().item<double>());
                    EXPECT_LT((ba.grad() - bb.grad()).abs().max().item<double>(),
                              1e-4 * bb.grad().abs().max().item<double>());
                }
            }
}

TEST(FastConvolution, GradientsOnlyForWhatNeedsThem) {
    // A frozen input (the network's first layer) gets no gradient; the weights still do.
    torch::manual_seed(1);
    const auto x = torch::randn({1, 3, 6, 6, 6});
    auto w = torch::randn({4, 3, 3, 3, 3}).requires_grad_(true);
    fastConvolution(x, w, torch::Tensor(), 1, 1).sum().backward();
    EXPECT_FALSE(x.grad().defined());
    ASSERT_TRUE(w.grad().defined());
    EXPECT_GT(w.grad().abs().sum().item<double>(), 0.0);
}

}  // namespace
}  // namespace lh::net
