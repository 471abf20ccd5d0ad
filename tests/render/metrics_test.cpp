#include "render/metrics.h"

#include "core/errors.h"
#include "render/image_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>
#include <unistd.h>

namespace lh {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A W x H image with every pixel set to `rgb` (linear).
ImageRGB uniform(int width, int height, float r, float g, float b) {
    ImageRGB image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float* p = image.at(x, y);
            p[0] = r, p[1] = g, p[2] = b;
        }
    return image;
}

// One pixel: the two RGB vectors whose angle is measured.
double angleOf(float r1, float g1, float b1, float r2, float g2, float b2) {
    return angularErrorDegrees(uniform(1, 1, r1, g1, b1), uniform(1, 1, r2, g2, b2));
}

TEST(Metrics, IdenticalImagesGiveInfinitePsnrAndZeroAngle) {
    const ImageRGB image = uniform(8, 4, 0.2f, 0.5f, 0.9f);
    EXPECT_EQ(psnr(image, image), kInf);
    EXPECT_EQ(angularErrorDegrees(image, image), 0.0);
}

TEST(Metrics, UniformSrgbErrorGivesHandComputedPsnr) {
    // sRGB 0.5 against sRGB 0.6 in every channel: MSE = 0.01, PSNR = 20 log10(1 / 0.1).
    const float gtLinear = srgbDecode(0.5f), predLinear = srgbDecode(0.6f);
    const ImageRGB gt = uniform(8, 4, gtLinear, gtLinear, gtLinear);
    EXPECT_NEAR(psnr(uniform(8, 4, predLinear, predLinear, predLinear), gt), 20.0, 1e-4);
    // Off by 0.01 in red only: MSE = 0.01^2 / 3, PSNR = 40 + 10 log10(3) dB.
    const float redLinear = srgbDecode(0.51f);
    EXPECT_NEAR(psnr(uniform(8, 4, redLinear, gtLinear, gtLinear), gt),
                40.0 + 10.0 * std::log10(3.0), 1e-3);
}

TEST(Metrics, PsnrClampsToTheDisplayRange) {
    EXPECT_EQ(psnr(uniform(4, 2, 5.f, 5.f, 5.f), uniform(4, 2, 1.f, 1.f, 1.f)), kInf);
    EXPECT_EQ(psnr(uniform(4, 2, -2.f, 0.f, 0.f), uniform(4, 2, 0.f, 0.f, 0.f)), kInf);
    // Above 1 against 0: the clamped error is the full peak, MSE 1, PSNR 0 dB.
    EXPECT_NEAR(psnr(uniform(4, 2, 3.f, 3.f, 3.f), uniform(4, 2, 0.f, 0.f, 0.f)), 0.0, 1e-12);
}

TEST(Metrics, AngularErrorOfKnownVectors) {
    EXPECT_NEAR(angleOf(1, 0, 0, 0, 1, 0), 90.0, 1e-12);
    EXPECT_NEAR(angleOf(1, 1, 0, 1, 0, 0), 45.0, 1e-12);
    EXPECT_NEAR(angleOf(0.3f, 0.2f, 0.1f, 0.6f, 0.4f, 0.2f), 0.0, 1e-12);  // 2x brighter
    EXPECT_NEAR(angleOf(1, 0, 0, -1, 0, 0), 180.0, 1e-12);
    // A tiny angle stays exact (acos of a dot product near 1 would lose it).
    EXPECT_NEAR(angleOf(1, 1e-4f, 0, 1, 0, 0), std::atan(double(1e-4f)) * 180.0 / M_PI, 1e-12);
}

TEST(Metrics, AngularErrorSkipsPixelsAtOrBelowNorm1e6) {
    ImageRGB pred = uniform(3, 1, 1.f, 0.f, 0.f), gt = uniform(3, 1, 1.f, 1.f, 0.f);  // 45 deg
    pred.at(1, 0)[0] = 1e-6f;  // pixel 1: dark prediction (would be 45 deg)
    gt.at(2, 0)[0] = 0.f, gt.at(2, 0)[1] = 5e-7f;  // pixel 2: dark truth (would be 90 deg)
    gt.at(0, 0)[1] = 0.f;  // pixel 0: exact, 0 deg
    EXPECT_NEAR(angularErrorDegrees(pred, gt), 0.0, 1e-12);  // only pixel 0 counts

    const ImageRGB black = uniform(3, 1, 0.f, 0.f, 0.f);
    EXPECT_TRUE(std::isnan(angularErrorDegrees(black, gt)));
}

TEST(Metrics, MaskRestrictsBothMetrics) {
    // Pixel 0 is exact; pixel 1 is off by sRGB 0.1 in every channel and by 90 degrees.
    const float half = srgbDecode(0.5f), more = srgbDecode(0.6f);
    ImageRGB pred = uniform(2, 1, half, 0.f, 0.f), gt = uniform(2, 1, half, 0.f, 0.f);
    pred.at(1, 0)[0] = more, pred.at(1, 0)[1] = more, pred.at(1, 0)[2] = more;
    gt.at(1, 0)[0] = 0.f, gt.at(1, 0)[1] = 0.f, gt.at(1, 0)[2] = half;  // blue vs white-ish
    const std::vector<std::uint8_t> onlyExact = {1, 0}, onlyWrong = {0, 1};

    EXPECT_EQ(psnr(pred, gt, &onlyExact), kInf);
    EXPECT_NEAR(angularErrorDegrees(pred, gt, &onlyExact), 0.0, 1e-12);
    // Pixel 1 alone: errors 0.6, 0.6, 0.1 -> MSE = 0.73 / 3; angle between (1,1,1) and z.
    const double mse = (0.36 + 0.36 + 0.01) / 3.0;
    const double angle = std::acos(1.0 / std::sqrt(3.0)) * 180.0 / M_PI;
    EXPECT_NEAR(psnr(pred, gt, &onlyWrong), -10.0 * std::log10(mse), 1e-4);
    EXPECT_NEAR(angularErrorDegrees(pred, gt, &onlyWrong), angle, 1e-4);
    // Unmasked: both pixels, half the squared error and half the mean angle.
    EXPECT_NEAR(psnr(pred, gt), -10.0 * std::log10(mse / 2.0), 1e-4);
    EXPECT_NEAR(angularErrorDegrees(pred, gt), angle / 2.0, 1e-4);
}

TEST(Metrics, EmptyMaskGivesNaN) {
    const ImageRGB image = uniform(2, 1, 0.5f, 0.5f, 0.5f);
    const std::vector<std::uint8_t> none = {0, 0};
    EXPECT_TRUE(std::isnan(psnr(image, image, &none)));
    EXPECT_TRUE(std::isnan(angularErrorDegrees(image, image, &none)));
}

TEST(Metrics, CompareEnvmapsFillsObservedOnlyWithAMask) {
    ImageRGB pred = uniform(2, 1, 1.f, 0.f, 0.f);
    const ImageRGB gt = uniform(2, 1, 1.f, 0.f, 0.f);
    pred.at(1, 0)[1] = 1.f;  // pixel 1: 45 degrees off
    const EnvmapMetrics all = compareEnvmaps(pred, gt);
    EXPECT_EQ(all.psnrAll, psnr(pred, gt));
    EXPECT_NEAR(all.angularAll, 22.5, 1e-12);
    EXPECT_TRUE(std::isnan(all.psnrObserved));
    EXPECT_TRUE(std::isnan(all.angularObserved));

    const std::vector<std::uint8_t> mask = {1, 0};
    const EnvmapMetrics observed = compareEnvmaps(pred, gt, &mask);
    EXPECT_EQ(observed.psnrAll, all.psnrAll);
    EXPECT_EQ(observed.psnrObserved, kInf);
    EXPECT_EQ(observed.angularObserved, 0.0);
}

TEST(Metrics, RejectsMismatchedOrNonFiniteInput) {
    const ImageRGB small = uniform(4, 2, 0.5f, 0.5f, 0.5f), large = uniform(8, 4, 0.5f, 0.5f, 0.5f);
    try {
        psnr(small, large);
        FAIL() << "size mismatch accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("4x2"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("8x4"), std::string::npos) << e.what();
    }
    EXPECT_THROW(angularErrorDegrees(small, large), InputError);
    EXPECT_THROW(compareEnvmaps(large, small), InputError);

    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        ImageRGB pred = small;
        pred.at(1, 1)[2] = bad;
        try {
            compareEnvmaps(pred, small);
            FAIL() << "non-finite prediction accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("prediction holds NaN/Inf"), std::string::npos);
        }
    }
    const std::vector<std::uint8_t> shortMask(3, 1);
    EXPECT_THROW(psnr(small, small, &shortMask), InputError);
}

TEST(Metrics, LoadMaskReadsNonzeroPixelsAndChecksTheSize) {
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("lh_metrics_mask_" + std::to_string(::getpid()) + ".png"))
                                 .string();
    ImageRGB image(3, 2);
    image.at(0, 0)[0] = 1.f;    // white-ish: observed
    image.at(2, 1)[1] = 0.01f;  // dim but nonzero: observed
    writePng(image, path);

    const std::vector<std::uint8_t> mask = loadMask(path, 3, 2);
    EXPECT_EQ(mask, (std::vector<std::uint8_t>{1, 0, 0, 0, 0, 1}));
    try {
        loadMask(path, 4, 2);
        FAIL() << "mask size mismatch accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("3x2"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("4x2"), std::string::npos) << e.what();
    }
    std::filesystem::remove(path);
    EXPECT_THROW(loadMask(path, 3, 2), FileError);
}

TEST(Metrics, MeanStdLeavesOutNaN) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const MeanStd s = meanStd({1.0, nan, 2.0, 3.0});
    EXPECT_DOUBLE_EQ(s.mean, 2.0);
    EXPECT_DOUBLE_EQ(s.std, std::sqrt(2.0 / 3.0));  // population standard deviation
    EXPECT_EQ(s.count, 3);
    EXPECT_EQ(s.nanCount, 1);

    const MeanStd none = meanStd({nan, nan});
    EXPECT_TRUE(std::isnan(none.mean));
    EXPECT_TRUE(std::isnan(none.std));
    EXPECT_EQ(none.count, 0);
    EXPECT_EQ(none.nanCount, 2);
}

}  // namespace
}  // namespace lh
