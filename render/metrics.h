// Envmap quality metrics, exactly as ../shared/CONVENTIONS.md ("Metrics") defines them:
// PSNR on sRGB-encoded clamped values and RGB angular error on linear values, over every
// pixel ("all content") or over the pixels of a mask ("observed content").
//
// A mask is one byte per pixel, row-major like ImageRGB; nonzero = observed.
// Pred and gt must have the same size and hold only finite values, and a mask must have
// one entry per pixel, or the functions throw InputError.
#pragma once

#include "render/image.h"

#include <cstdint>
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

// The four numbers the paper reports per envmap. The observed ones are NaN without a mask.
struct EnvmapMetrics {
    double psnrAll;          // dB
    double angularAll;       // degrees
    double psnrObserved;     // dB
    double angularObserved;  // degrees
};

EnvmapMetrics compareEnvmaps(const ImageRGB& pred, const ImageRGB& gt,
                             const std::vector<std::uint8_t>* mask = nullptr);

// Reads an observed-pixel mask (a PNG, or any image readImage reads): a pixel is observed
// when any channel is nonzero. Throws FileError if unreadable, InputError unless it is
// width x height.
std::vector<std::uint8_t> loadMask(const std::string& path, int width, int height);

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
