// Envmap quality metrics, exactly as docs/conventions.md#metrics defines them:
// PSNR on sRGB-encoded clamped values and RGB angular error on linear values, over every
// pixel ("all content") or over the pixels of a mask ("observed content"). Two HDR metrics
// see what clamped PSNR cannot (lamps and windows far above 1): the relative error of the
// diffuse irradiance at six axis normals, and the RMSE of log(1 + luminance). docs/metrics.md
// defines all of them.
//
// A mask is one byte per pixel, row-major like ImageRGB; nonzero = observed.
// Pred and gt must have the same size and hold only finite values, and a mask must have
// one entry per pixel, or the functions throw InputError.
#pragma once

#include "image/highlights.h"
#include "image/image.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace lh {

// PSNR in dB, peak 1, of srgbEncode(clamp(linear, 0, 1)); the MSE runs over all pixels and
// channels, or over the masked pixels only. Identical images (after clamping) give +infinity;
// a mask with no observed pixel gives NaN, which callers report as "no observed pixels".
double psnr(const ImageRGB& pred, const ImageRGB& gt,
            const std::vector<std::uint8_t>* mask = nullptr);

// Mean over pixels of the angle, in degrees, between the predicted and the true linear RGB
// vectors. Only pixels where both vectors have a norm above 1e-6 (and that are in the mask)
// count; with no such pixel the result is NaN.
double angularErrorDegrees(const ImageRGB& pred, const ImageRGB& gt,
                           const std::vector<std::uint8_t>* mask = nullptr);

// Mean over pixels (all, or those in the mask) and channels of the signed difference of the
// displayed values, srgbEncode(clamp(pred)) - srgbEncode(clamp(gt)), in [-1, 1]: positive
// when the prediction is brighter than the truth, as PSNR sees it. NaN for an empty mask.
double displayBias(const ImageRGB& pred, const ImageRGB& gt,
                   const std::vector<std::uint8_t>* mask = nullptr);

// The PSNR (dB) of the same pixels with their display bias taken out: from psnr(pred, gt, mask)
// and displayBias(pred, gt, mask), 10 log10(1 / (MSE - bias^2)), the variance of the displayed
// differences in place of their mean square. It says how much of a PSNR is one wrong overall
// brightness: far above `psnrDb`, mostly that; close to it, mostly wrong structure. +inf
// where every difference is the same; NaN where either input is.
double psnrWithoutBias(double psnrDb, double bias);

// The six axis normals of the irradiance metric, in this order (world frame, OpenCV axes:
// +y is down).
enum class AxisNormal { PlusX, MinusX, PlusY, MinusY, PlusZ, MinusZ };
constexpr int kAxisNormals = 6;

// Diffuse irradiance of an equirectangular envmap (docs/conventions.md#envmap-layout) at normal n,
// per RGB channel: E(n) = sum over pixels of L(d) max(0, n.d) dOmega, with the pixel's solid angle
// dOmega = (2 pi / W) (pi / H) sin phi. Units: radiance times steradians (a constant L = 1 gives
// pi). Throws InputError for an empty or non-finite envmap.
struct AxisIrradiance {
    double rgb[kAxisNormals][3];  // [AxisNormal][channel]
    const double* at(AxisNormal n) const { return rgb[int(n)]; }
};
AxisIrradiance axisIrradiance(const ImageRGB& envmap);

// Smallest true irradiance (radiance x sr) a relative error is taken against: a darker
// (normal, channel) term of the ground truth is left out of the mean, since dividing by
// next to nothing would let one black wall outweigh the whole map.
constexpr double kMinIrradiance = 1e-6;

// Mean over the 6 normals and 3 channels of |E_pred - E_gt| / E_gt (a ratio; 1.0 = off by
// the truth's own size), over the terms with E_gt > kMinIrradiance; NaN when there is none
// (a black ground truth).
double irradianceError(const ImageRGB& pred, const ImageRGB& gt);

// Root mean square over pixels (all, or those in the mask) of ln(1 + Y_pred) - ln(1 + Y_gt),
// Y = 0.2126 R + 0.7152 G + 0.0722 B of the linear radiance, a negative Y counted as 0.
// Natural log units; NaN for a mask with no observed pixel.
double logLuminanceRmse(const ImageRGB& pred, const ImageRGB& gt,
                        const std::vector<std::uint8_t>* mask = nullptr);

// How much light the prediction holds against the truth: the ratio of their mean luminance
// over the sphere (each pixel weighted by its solid angle, negative luminance counted as 0).
// 1 = the right total energy, 0.5 = half the truth's; it says nothing of where the light is.
// PSNR (clamped) cannot tell a lamp of 2 from one of 200; this can. NaN when the truth's mean
// luminance is at most kMinIrradiance / (4 pi) (a black ground truth).
double meanRadianceRatio(const ImageRGB& pred, const ImageRGB& gt);

// The four numbers the paper reports per envmap, the HDR ones, and PSNR and display bias over
// the unobserved pixels. The observed and unobserved ones
// are NaN without a mask. Irradiance is an integral over the whole sphere, so it has no
// observed variant.
struct EnvmapMetrics {
    double psnrAll;                                                          // dB
    double angularAll;                                                       // degrees
    double psnrObserved;                                                     // dB
    double angularObserved;                                                  // degrees
    double irradianceError = std::numeric_limits<double>::quiet_NaN();       // ratio
    double logLuminanceAll = std::numeric_limits<double>::quiet_NaN();       // ln units
    double logLuminanceObserved = std::numeric_limits<double>::quiet_NaN();  // ln units
    double radianceRatio = std::numeric_limits<double>::quiet_NaN();         // ratio
    // Where the mask is zero: what a predictor had to invent.
    double psnrUnobserved = std::numeric_limits<double>::quiet_NaN();         // dB
    double displayBiasUnobserved = std::numeric_limits<double>::quiet_NaN();  // sRGB units
    // Lamps and windows (image/highlights.h): the shares of the true and the predicted
    // highlights that the other shows within the radius compareEnvmaps was given.
    double highlightRecall = std::numeric_limits<double>::quiet_NaN();     // ratio
    double highlightPrecision = std::numeric_limits<double>::quiet_NaN();  // ratio
};

// Highlights are matched within `highlightRadiusDegrees` (image/highlights.h).
EnvmapMetrics compareEnvmaps(const ImageRGB& pred, const ImageRGB& gt,
                             const std::vector<std::uint8_t>* mask = nullptr,
                             double highlightRadiusDegrees = kHighlightRadiusDegrees);

// The numbers of `m` in the column order of `compare --csv` and eval's metrics.csv, and those
// columns' names. New columns go at the end, so scripts that index the first ones keep working.
constexpr std::size_t kEnvmapMetricColumns = 12;
std::array<double, kEnvmapMetricColumns> metricColumns(const EnvmapMetrics& m);
constexpr std::array<const char*, kEnvmapMetricColumns> kEnvmapMetricColumnNames = {
    "psnr_all_db",        "angular_all_deg",       "psnr_observed_db",     "angular_observed_deg",
    "log_lum_rmse_all",   "log_lum_rmse_observed", "irradiance_rel_error", "radiance_ratio",
    "psnr_unobserved_db", "srgb_bias_unobserved",  "highlight_recall",     "highlight_precision"};
// The names joined by commas: the end of a CSV header.
std::string metricColumnsCsvHeader();

// Reads an observed-pixel mask (a PNG, or any image readImage reads): a pixel is observed
// when any channel is nonzero. Throws FileError if unreadable, InputError unless it is
// width x height.
std::vector<std::uint8_t> loadMask(const std::string& path, int width, int height);
// The converse: a width x height image, white where the mask is nonzero, black elsewhere (what
// `synth` writes as env_K_mask.png, and what training resizes to its envmap size).
ImageRGB maskToImage(const std::vector<std::uint8_t>& mask, int width, int height);

// Mean and population standard deviation of one metric over a test set. NaN entries (an
// envmap without observed pixels) are left out and counted in `nanCount`. An infinite entry
// (a perfect prediction's PSNR) makes the mean infinite and the std NaN. With no usable
// entry both are NaN.
struct MeanStd {
    double mean;
    double std;
    int count;     // entries used
    int nanCount;  // NaN entries left out
};

MeanStd meanStd(const std::vector<double>& values);

}  // namespace lh
