#include "image/metrics.h"

#include "core/errors.h"
#include "image/envmap_layout.h"
#include "image/highlights.h"
#include "image/image_io.h"
#include "image/irradiance_weights.h"
#include "image/luminance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace lh {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMinNorm = 1e-6;  // docs/conventions.md#metrics: angular error skips darker pixels

std::string sizeText(const ImageRGB& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

bool allFinite(const ImageRGB& image) {
    return std::all_of(image.pixels.begin(), image.pixels.end(),
                       [](float v) { return std::isfinite(v); });
}

// Every public metric starts here, so none of them silently compares mismatched data.
void checkComparable(const ImageRGB& pred, const ImageRGB& gt,
                     const std::vector<std::uint8_t>* mask) {
    if (pred.width != gt.width || pred.height != gt.height)
        throw InputError("prediction is " + sizeText(pred) + " but ground truth is " +
                         sizeText(gt));
    if (!allFinite(pred)) throw InputError("prediction holds NaN/Inf");
    if (!allFinite(gt)) throw InputError("ground truth holds NaN/Inf");
    const std::size_t pixels = std::size_t(gt.width) * gt.height;
    if (mask && mask->size() != pixels)
        throw InputError("mask has " + std::to_string(mask->size()) + " entries for a " +
                         sizeText(gt) + " envmap");
}

bool counts(const std::vector<std::uint8_t>* mask, std::size_t pixel) {
    return !mask || (*mask)[pixel] != 0;
}

double displayValue(float linear) { return srgbEncode(std::clamp(linear, 0.0f, 1.0f)); }

// atan2 of the cross and dot products stays accurate near 0 and 180 degrees, where acos of
// the normalised dot product loses half its digits.
double angleDegrees(const float* a, const float* b) {
    const double ax = a[0], ay = a[1], az = a[2], bx = b[0], by = b[1], bz = b[2];
    const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    const double cross = std::sqrt(cx * cx + cy * cy + cz * cz);
    const double dot = ax * bx + ay * by + az * bz;
    return std::atan2(cross, dot) * 180.0 / M_PI;
}

double norm(const float* v) {
    return std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
}

// Rec. 709 luminance of linear RGB, negatives (a broken prediction's) counted as 0 so that
// ln(1 + Y) stays defined.
double luminance(const float* rgb) { return std::max(rec709Luminance(rgb), 0.0); }

}  // namespace

namespace {

// Sums over the counted pixels' channels of the displayed difference
// d = displayValue(pred) - displayValue(gt): PSNR reads the squares, the display bias the
// signed values.
struct DisplayDifferences {
    double sum = 0.0, squares = 0.0;
    std::size_t values = 0;
};

DisplayDifferences displayDifferences(const ImageRGB& pred, const ImageRGB& gt,
                                      const std::vector<std::uint8_t>* mask) {
    checkComparable(pred, gt, mask);
    DisplayDifferences s;
    const std::size_t pixels = std::size_t(gt.width) * gt.height;
    for (std::size_t p = 0; p < pixels; ++p) {
        if (!counts(mask, p)) continue;
        for (std::size_t i = 3 * p; i < 3 * p + 3; ++i) {
            const double d = displayValue(pred.pixels[i]) - displayValue(gt.pixels[i]);
            s.sum += d;
            s.squares += d * d;
        }
        s.values += 3;
    }
    return s;
}

double psnrOf(const DisplayDifferences& s) {
    if (s.values == 0) return kNaN;
    if (s.squares == 0.0) return std::numeric_limits<double>::infinity();
    return -10.0 * std::log10(s.squares / double(s.values));  // peak 1: 10 log10(1 / MSE)
}

double biasOf(const DisplayDifferences& s) {
    return s.values == 0 ? kNaN : s.sum / double(s.values);
}

}  // namespace

double psnr(const ImageRGB& pred, const ImageRGB& gt, const std::vector<std::uint8_t>* mask) {
    return psnrOf(displayDifferences(pred, gt, mask));
}

double displayBias(const ImageRGB& pred, const ImageRGB& gt,
                   const std::vector<std::uint8_t>* mask) {
    return biasOf(displayDifferences(pred, gt, mask));
}

double psnrWithoutBias(double psnrDb, double bias) {
    if (std::isnan(psnrDb) || std::isnan(bias)) return kNaN;
    const double meanSquare = std::pow(10.0, -psnrDb / 10.0);
    const double variance = meanSquare - bias * bias;
    // Rounding can leave a hair below zero where every difference is the same.
    if (!(variance > 1e-12 * meanSquare)) return std::numeric_limits<double>::infinity();
    return -10.0 * std::log10(variance);
}

double angularErrorDegrees(const ImageRGB& pred, const ImageRGB& gt,
                           const std::vector<std::uint8_t>* mask) {
    checkComparable(pred, gt, mask);
    double sum = 0.0;
    std::size_t used = 0;
    const std::size_t pixels = std::size_t(gt.width) * gt.height;
    for (std::size_t p = 0; p < pixels; ++p) {
        const float* a = &pred.pixels[3 * p];
        const float* b = &gt.pixels[3 * p];
        if (!counts(mask, p) || norm(a) <= kMinNorm || norm(b) <= kMinNorm) continue;
        sum += angleDegrees(a, b);
        ++used;
    }
    return used == 0 ? kNaN : sum / double(used);
}

AxisIrradiance axisIrradiance(const ImageRGB& envmap) {
    if (envmap.empty()) throw InputError("cannot integrate the irradiance of an empty envmap");
    if (!allFinite(envmap)) throw InputError("envmap holds NaN/Inf");
    AxisIrradiance result{};
    const std::vector<double> weights = axisIrradianceWeights(envmap.width, envmap.height);
    const std::size_t pixels = std::size_t(envmap.width) * envmap.height;
    for (std::size_t p = 0; p < pixels; ++p) {
        const float* radiance = &envmap.pixels[3 * p];
        const double* weight = &weights[p * kAxisNormals];
        for (int n = 0; n < kAxisNormals; ++n) {
            if (weight[n] == 0.0) continue;
            for (int ch = 0; ch < 3; ++ch) result.rgb[n][ch] += weight[n] * radiance[ch];
        }
    }
    return result;
}

double irradianceError(const ImageRGB& pred, const ImageRGB& gt) {
    checkComparable(pred, gt, nullptr);
    const AxisIrradiance p = axisIrradiance(pred), g = axisIrradiance(gt);
    double sum = 0.0;
    int terms = 0;
    for (int n = 0; n < kAxisNormals; ++n)
        for (int ch = 0; ch < 3; ++ch) {
            if (!(g.rgb[n][ch] > kMinIrradiance)) continue;
            sum += std::abs(p.rgb[n][ch] - g.rgb[n][ch]) / g.rgb[n][ch];
            ++terms;
        }
    return terms == 0 ? kNaN : sum / terms;
}

double logLuminanceRmse(const ImageRGB& pred, const ImageRGB& gt,
                        const std::vector<std::uint8_t>* mask) {
    checkComparable(pred, gt, mask);
    double squares = 0.0;
    std::size_t used = 0;
    const std::size_t pixels = std::size_t(gt.width) * gt.height;
    for (std::size_t p = 0; p < pixels; ++p) {
        if (!counts(mask, p)) continue;
        // log1p keeps the digits of a dim pixel, where ln(1 + Y) is close to Y.
        const double d =
            std::log1p(luminance(&pred.pixels[3 * p])) - std::log1p(luminance(&gt.pixels[3 * p]));
        squares += d * d;
        ++used;
    }
    return used == 0 ? kNaN : std::sqrt(squares / double(used));
}

double meanRadianceRatio(const ImageRGB& pred, const ImageRGB& gt) {
    checkComparable(pred, gt, nullptr);
    // Mean of Y over the sphere: each row weighted by sin(phi), the solid angle of its pixels
    // up to a factor common to all.
    const auto meanLuminance = [](const ImageRGB& image) {
        double sum = 0.0, weight = 0.0;
        for (int r = 0; r < image.height; ++r) {
            const double sinPhi = std::sin(envmapPolarAngle(r + 0.5, image.height));
            double row = 0.0;
            for (int c = 0; c < image.width; ++c) row += luminance(image.at(c, r));
            sum += sinPhi * row;
            weight += sinPhi * image.width;
        }
        return sum / weight;
    };
    const double truth = meanLuminance(gt);
    if (!(truth > kMinIrradiance / (4.0 * M_PI))) return kNaN;
    return meanLuminance(pred) / truth;
}

std::array<double, kEnvmapMetricColumns> metricColumns(const EnvmapMetrics& m) {
    return {m.psnrAll,         m.angularAll,
            m.psnrObserved,    m.angularObserved,
            m.logLuminanceAll, m.logLuminanceObserved,
            m.irradianceError, m.radianceRatio,
            m.psnrUnobserved,  m.displayBiasUnobserved,
            m.highlightRecall, m.highlightPrecision};
}

std::string metricColumnsCsvHeader() {
    std::string header;
    for (const char* name : kEnvmapMetricColumnNames)
        header += std::string(header.empty() ? "" : ",") + name;
    return header;
}

EnvmapMetrics compareEnvmaps(const ImageRGB& pred, const ImageRGB& gt,
                             const std::vector<std::uint8_t>* mask, double highlightRadiusDegrees) {
    EnvmapMetrics m{psnr(pred, gt),
                    angularErrorDegrees(pred, gt),
                    kNaN,
                    kNaN,
                    irradianceError(pred, gt),
                    logLuminanceRmse(pred, gt),
                    kNaN};
    if (mask) {
        m.psnrObserved = psnr(pred, gt, mask);
        m.angularObserved = angularErrorDegrees(pred, gt, mask);
        m.logLuminanceObserved = logLuminanceRmse(pred, gt, mask);
        std::vector<std::uint8_t> unobserved(mask->size());
        for (std::size_t p = 0; p < unobserved.size(); ++p) unobserved[p] = (*mask)[p] == 0;
        const DisplayDifferences invented = displayDifferences(pred, gt, &unobserved);
        m.psnrUnobserved = psnrOf(invented);
        m.displayBiasUnobserved = biasOf(invented);
    }
    m.radianceRatio = meanRadianceRatio(pred, gt);
    const HighlightMatch highlights = matchHighlights(pred, gt, highlightRadiusDegrees);
    m.highlightRecall = highlights.recall;
    m.highlightPrecision = highlights.precision;
    return m;
}

std::vector<std::uint8_t> loadMask(const std::string& path, int width, int height) {
    const ImageRGB image = readImage(path);
    if (image.width != width || image.height != height)
        throw InputError("mask '" + path + "' is " + sizeText(image) + " but the envmap is " +
                         std::to_string(width) + "x" + std::to_string(height));
    std::vector<std::uint8_t> mask(std::size_t(width) * height);
    for (std::size_t p = 0; p < mask.size(); ++p) {
        const float* v = &image.pixels[3 * p];
        mask[p] = v[0] > 0.f || v[1] > 0.f || v[2] > 0.f;
    }
    return mask;
}

ImageRGB maskToImage(const std::vector<std::uint8_t>& mask, int width, int height) {
    ImageRGB image(width, height);
    for (std::size_t p = 0; p < mask.size(); ++p)
        std::fill_n(&image.pixels[3 * p], 3, mask[p] ? 1.f : 0.f);
    return image;
}

MeanStd meanStd(const std::vector<double>& values) {
    MeanStd result{kNaN, kNaN, 0, 0};
    double sum = 0.0;
    for (double v : values) {
        if (std::isnan(v)) {
            ++result.nanCount;
        } else {
            sum += v;
            ++result.count;
        }
    }
    if (result.count == 0) return result;
    result.mean = sum / result.count;
    double squares = 0.0;  // second pass: no cancellation, unlike E[x^2] - E[x]^2
    for (double v : values)
        if (!std::isnan(v)) squares += (v - result.mean) * (v - result.mean);
    result.std = std::sqrt(squares / result.count);
    return result;
}

}  // namespace lh
