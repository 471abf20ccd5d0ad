#include "image/metrics.h"

#include "core/errors.h"
#include "image/envmap_layout.h"
#include "image/image_io.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

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
    pred.at(1, 0)[0] = 1e-6f;                      // pixel 1: dark prediction (would be 45 deg)
    gt.at(2, 0)[0] = 0.f, gt.at(2, 0)[1] = 5e-7f;  // pixel 2: dark truth (would be 90 deg)
    gt.at(0, 0)[1] = 0.f;                          // pixel 0: exact, 0 deg
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

    for (float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
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

// What synth writes as env_K_mask.png reads back as the same mask.
TEST(Metrics, MaskToImageIsWhereObservedAndLoadMaskReadsItBack) {
    const std::vector<std::uint8_t> mask = {1, 0, 0, 0, 3, 1};
    const ImageRGB image = maskToImage(mask, 3, 2);
    ASSERT_EQ(image.width, 3);
    ASSERT_EQ(image.height, 2);
    EXPECT_FLOAT_EQ(image.at(0, 0)[2], 1.f);
    EXPECT_FLOAT_EQ(image.at(1, 0)[0], 0.f);
    EXPECT_FLOAT_EQ(image.at(1, 1)[1], 1.f) << "any nonzero byte is observed";
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("lh_metrics_mask_image_" + std::to_string(::getpid()) + ".png"))
                                 .string();
    writePng(image, path);
    EXPECT_EQ(loadMask(path, 3, 2), (std::vector<std::uint8_t>{1, 0, 0, 0, 1, 1}));
    std::filesystem::remove(path);
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

// ---- HDR metrics: diffuse irradiance at the six axis normals, log-luminance RMSE ---------

// The pixel discretisation of the hemisphere integral: at 240x120 the midpoint rule with the
// kinks of max(0, n.d) on pixel boundaries is good to about 1e-4 relative.
constexpr double kIrradianceTolerance = 2e-4;

TEST(HdrMetrics, ConstantRadianceGivesPiAtEveryNormal) {
    const AxisIrradiance e = axisIrradiance(uniform(240, 120, 1.f, 2.f, 0.5f));
    for (int n = 0; n < kAxisNormals; ++n) {
        EXPECT_NEAR(e.rgb[n][0], M_PI, M_PI * kIrradianceTolerance) << "normal " << n;
        EXPECT_NEAR(e.rgb[n][1], 2.0 * M_PI, 2.0 * M_PI * kIrradianceTolerance) << "normal " << n;
        EXPECT_NEAR(e.rgb[n][2], 0.5 * M_PI, 0.5 * M_PI * kIrradianceTolerance) << "normal " << n;
    }
}

TEST(HdrMetrics, BrightCapAtPlusXLightsOnlyPlusX) {
    // Radiance 1 within alpha = 30 degrees of +x, 0 elsewhere. In polar coordinates about +x
    // (beta from the axis): E(+x) = integral of cos(beta) = pi sin^2(alpha) = pi / 4; -x sees
    // none of the cap; each side normal (+-y, +-z) gets the integral of sin(beta) cos(psi)
    // over its half of the cap, 2 * integral_0^alpha sin^2(beta) = alpha - sin(2 alpha) / 2.
    const int width = 480, height = 240;
    const double alpha = M_PI / 6.0;
    ImageRGB envmap(width, height);
    for (int r = 0; r < height; ++r)
        for (int c = 0; c < width; ++c)
            if (envmapPixelDirection(r, c, width, height).x() > std::cos(alpha))
                std::fill_n(envmap.at(c, r), 3, 1.f);
    const AxisIrradiance e = axisIrradiance(envmap);
    // The cap's rim cuts through pixels: 3% is the staircase at this size.
    EXPECT_NEAR(e.at(AxisNormal::PlusX)[0], M_PI / 4.0, 0.03 * M_PI / 4.0);
    EXPECT_EQ(e.at(AxisNormal::MinusX)[0], 0.0);
    const double side = alpha - std::sin(2.0 * alpha) / 2.0;
    for (AxisNormal n :
         {AxisNormal::PlusY, AxisNormal::MinusY, AxisNormal::PlusZ, AxisNormal::MinusZ})
        EXPECT_NEAR(e.at(n)[1], side, 0.03 * side) << "normal " << int(n);
}

TEST(HdrMetrics, PlusYIsDownAndSeesOnlyTheLowerHalf) {
    // OpenCV axes: +y is down, and row 0 looks up. A lit lower half (rows H/2..H-1) gives
    // E(+y) = pi and E(-y) = 0.
    const int width = 240, height = 120;
    ImageRGB envmap(width, height);
    for (int r = height / 2; r < height; ++r)
        for (int c = 0; c < width; ++c) std::fill_n(envmap.at(c, r), 3, 1.f);
    const AxisIrradiance e = axisIrradiance(envmap);
    EXPECT_NEAR(e.at(AxisNormal::PlusY)[0], M_PI, M_PI * kIrradianceTolerance);
    EXPECT_EQ(e.at(AxisNormal::MinusY)[0], 0.0);
    EXPECT_NEAR(e.at(AxisNormal::PlusX)[0], M_PI / 2.0, M_PI / 2.0 * kIrradianceTolerance);
}

TEST(HdrMetrics, IrradianceErrorIsRelativeToTheTruth) {
    const ImageRGB gt = uniform(64, 32, 3.f, 0.2f, 50.f);
    EXPECT_EQ(irradianceError(gt, gt), 0.0);
    EXPECT_NEAR(irradianceError(uniform(64, 32, 6.f, 0.4f, 100.f), gt), 1.0, 1e-9);  // 2x
    EXPECT_NEAR(irradianceError(uniform(64, 32, 1.5f, 0.1f, 25.f), gt), 0.5, 1e-9);  // half
    // Off in one channel only: that channel's 6 terms are 1.0, the other 12 are 0.
    EXPECT_NEAR(irradianceError(uniform(64, 32, 6.f, 0.2f, 50.f), gt), 1.0 / 3.0, 1e-9);
    // PSNR cannot tell a lamp of 50 from one of 100 (both clamp to 1); this metric can.
    EXPECT_EQ(psnr(uniform(64, 32, 1.f, 1.f, 100.f), uniform(64, 32, 1.f, 1.f, 50.f)), kInf);
}

TEST(HdrMetrics, IrradianceErrorLeavesOutDarkTruthTerms) {
    // Ground truth lit only in its lower half: E_gt(-y) = 0 is left out, the other 5 normals
    // count. A prediction twice the truth is off by 1.0 on each of them; a prediction that
    // also lights the upper half is penalised only through the side normals.
    const int width = 240, height = 120;
    ImageRGB gt(width, height);
    for (int r = height / 2; r < height; ++r)
        for (int c = 0; c < width; ++c) std::fill_n(gt.at(c, r), 3, 1.f);
    ImageRGB twice = gt;
    for (float& v : twice.pixels) v *= 2.f;
    EXPECT_NEAR(irradianceError(twice, gt), 1.0, 1e-9);
    // Lit everywhere: E(+y) unchanged (pi vs pi), the 4 side normals pi vs pi/2 (error 1).
    EXPECT_NEAR(irradianceError(uniform(width, height, 1.f, 1.f, 1.f), gt), 4.0 / 5.0, 1e-3);
    // A black truth has no term at all.
    const ImageRGB black(width, height);
    EXPECT_TRUE(std::isnan(irradianceError(twice, black)));
}

TEST(HdrMetrics, LogLuminanceRmseOfAConstantOffset) {
    const ImageRGB gt = uniform(16, 8, 0.5f, 0.5f, 0.5f);  // Y = 0.5
    EXPECT_EQ(logLuminanceRmse(gt, gt), 0.0);
    // Y = 0.2126 * 4 + 0.7152 * 2 + 0.0722 * 1 = 2.353 against Y = 0.5, at every pixel.
    const ImageRGB pred = uniform(16, 8, 4.f, 2.f, 1.f);
    const double expected = std::log(1.0 + 2.353) - std::log(1.5);
    EXPECT_NEAR(logLuminanceRmse(pred, gt), expected, 1e-6);
    EXPECT_NEAR(logLuminanceRmse(gt, pred), expected, 1e-6);  // symmetric
    // Negative luminance counts as 0: ln(1 + 0) - ln(1.5).
    EXPECT_NEAR(logLuminanceRmse(uniform(16, 8, -1.f, -1.f, -1.f), gt), std::log(1.5), 1e-6);
}

TEST(HdrMetrics, LogLuminanceRmseIsARootMeanSquareAndHonoursTheMask) {
    // Pixel 0 exact (Y = 0), pixel 1 at Y = e - 1 against 0: difference 1. RMSE = sqrt(1/2).
    ImageRGB pred(2, 1), gt(2, 1);
    std::fill_n(pred.at(1, 0), 3, float(M_E - 1.0));  // grey: Y = R = G = B
    EXPECT_NEAR(logLuminanceRmse(pred, gt), std::sqrt(0.5), 1e-6);
    const std::vector<std::uint8_t> onlyWrong = {0, 1}, onlyExact = {1, 0}, none = {0, 0};
    EXPECT_NEAR(logLuminanceRmse(pred, gt, &onlyWrong), 1.0, 1e-6);
    EXPECT_EQ(logLuminanceRmse(pred, gt, &onlyExact), 0.0);
    EXPECT_TRUE(std::isnan(logLuminanceRmse(pred, gt, &none)));
}

TEST(HdrMetrics, MeanRadianceRatioWeighsPixelsBySolidAngle) {
    const ImageRGB gt = uniform(64, 32, 0.5f, 0.5f, 0.5f);
    EXPECT_NEAR(meanRadianceRatio(gt, gt), 1.0, 1e-12);
    EXPECT_NEAR(meanRadianceRatio(uniform(64, 32, 0.25f, 0.25f, 0.25f), gt), 0.5, 1e-9);
    // Luminance, not RGB: pure blue of 1 has Y = 0.0722.
    EXPECT_NEAR(meanRadianceRatio(uniform(64, 32, 0.f, 0.f, 1.f), gt), 0.0722 / 0.5, 1e-6);
    // The same lamp (one pixel of 1000) on the horizon row and on the top row: the top row's
    // pixels are smaller (sin(phi) of its centre against about 1), so it adds less light.
    ImageRGB horizon = gt, top = gt;
    std::fill_n(horizon.at(10, 16), 3, 1000.f);
    std::fill_n(top.at(10, 0), 3, 1000.f);
    const double horizonExtra = meanRadianceRatio(horizon, gt) - 1.0,
                 topExtra = meanRadianceRatio(top, gt) - 1.0;
    EXPECT_GT(horizonExtra, 0.0);
    EXPECT_NEAR(topExtra / horizonExtra, std::sin(M_PI * 0.5 / 32) / std::sin(M_PI * 16.5 / 32),
                1e-6);
    // A black truth: no ratio.
    EXPECT_TRUE(std::isnan(meanRadianceRatio(gt, ImageRGB(64, 32))));
    EXPECT_THROW(meanRadianceRatio(uniform(4, 2, 1.f, 1.f, 1.f), gt), InputError);
}

TEST(HdrMetrics, CompareEnvmapsFillsTheHdrFields) {
    const ImageRGB gt = uniform(32, 16, 0.5f, 0.5f, 0.5f);
    const ImageRGB pred = uniform(32, 16, 1.f, 1.f, 1.f);
    const EnvmapMetrics all = compareEnvmaps(pred, gt);
    EXPECT_NEAR(all.irradianceError, 1.0, 1e-9);
    EXPECT_NEAR(all.logLuminanceAll, std::log(2.0) - std::log(1.5), 1e-6);
    EXPECT_TRUE(std::isnan(all.logLuminanceObserved));
    const std::vector<std::uint8_t> none(32 * 16, 0);
    const EnvmapMetrics masked = compareEnvmaps(pred, gt, &none);
    EXPECT_TRUE(std::isnan(masked.logLuminanceObserved));
    EXPECT_EQ(masked.irradianceError, all.irradianceError);
    EXPECT_NEAR(all.radianceRatio, 2.0, 1e-9);
    EXPECT_THROW(irradianceError(uniform(4, 2, 1.f, 1.f, 1.f), gt), InputError);
}

TEST(Metrics, UnobservedPixelsGetTheirOwnPsnrAndDisplayBias) {
    // Truth 0.25 everywhere (displayed as srgbEncode(0.25) = 0.537); the prediction is exact on
    // the observed left half and white (displayed 1) on the unobserved right half.
    const int w = 8, h = 4;
    const ImageRGB gt = uniform(w, h, 0.25f, 0.25f, 0.25f);
    ImageRGB pred = gt;
    std::vector<std::uint8_t> mask(std::size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (x < w / 2)
                mask[std::size_t(y) * w + x] = 1;
            else
                std::fill_n(pred.at(x, y), 3, 1.f);
        }
    const double gap = 1.0 - srgbEncode(0.25f);
    const EnvmapMetrics m = compareEnvmaps(pred, gt, &mask);
    EXPECT_TRUE(std::isinf(m.psnrObserved));
    EXPECT_NEAR(m.psnrUnobserved, -10.0 * std::log10(gap * gap), 1e-4);
    EXPECT_NEAR(m.displayBiasUnobserved, gap, 1e-6);
    // Signed: the other way round it is as dark as it was bright.
    EXPECT_NEAR(compareEnvmaps(gt, pred, &mask).displayBiasUnobserved, -gap, 1e-6);
    // Over all pixels the bias halves; without a mask there is no unobserved part.
    EXPECT_NEAR(displayBias(pred, gt), gap / 2, 1e-6);
    const EnvmapMetrics unmasked = compareEnvmaps(pred, gt);
    EXPECT_TRUE(std::isnan(unmasked.psnrUnobserved));
    EXPECT_TRUE(std::isnan(unmasked.displayBiasUnobserved));
    // Everything observed: nothing left to invent.
    const std::vector<std::uint8_t> all(std::size_t(w) * h, 1);
    EXPECT_TRUE(std::isnan(compareEnvmaps(pred, gt, &all).psnrUnobserved));
}

TEST(Metrics, PsnrWithoutBiasKeepsOnlyTheStructure) {
    // Truth displayed at 0.5 everywhere. A prediction 0.2 brighter everywhere is all bias (no
    // structure left: +inf); one that alternates 0.3 and 0.7 has no bias (the PSNR stays); one
    // that alternates 0.5 and 0.9 has bias 0.2 and a structure of +-0.2 (PSNR 10 log10(1 /
    // 0.04) = 13.98 dB, 10 log10(1 / 0.08) = 10.97 dB with the bias).
    const int w = 8, h = 4;
    const float truth = srgbDecode(0.5f);
    const ImageRGB gt = uniform(w, h, truth, truth, truth);
    const auto displayed = [&](float even, float odd) {
        ImageRGB image = gt;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                std::fill_n(image.at(x, y), 3, srgbDecode((x + y) % 2 ? odd : even));
        return image;
    };
    const auto withoutBias = [&](const ImageRGB& pred) {
        return psnrWithoutBias(psnr(pred, gt), displayBias(pred, gt));
    };
    const ImageRGB brighter = displayed(0.7f, 0.7f);
    EXPECT_NEAR(psnr(brighter, gt), -10.0 * std::log10(0.04), 1e-3);
    EXPECT_TRUE(std::isinf(withoutBias(brighter)));
    const ImageRGB unbiased = displayed(0.3f, 0.7f);
    EXPECT_NEAR(withoutBias(unbiased), psnr(unbiased, gt), 1e-3);
    const ImageRGB both = displayed(0.5f, 0.9f);
    EXPECT_NEAR(psnr(both, gt), -10.0 * std::log10(0.08), 1e-3);
    EXPECT_NEAR(withoutBias(both), -10.0 * std::log10(0.04), 1e-3);
    EXPECT_TRUE(std::isinf(psnrWithoutBias(INFINITY, 0.0)));  // an exact prediction
    EXPECT_TRUE(std::isnan(psnrWithoutBias(NAN, 0.1)));
    EXPECT_TRUE(std::isnan(psnrWithoutBias(20.0, NAN)));
}

}  // namespace
}  // namespace lh
