#include "image/truth_splice.h"

#include "core/errors.h"
#include "image/luminance.h"

#include <cmath>
#include <string>

namespace lh {

const char* truthPartName(TruthPart part) {
    switch (part) {
        case TruthPart::Observed:
            return "true observed pixels";
        case TruthPart::Unobserved:
            return "true unobserved pixels";
        case TruthPart::LampsAndWindows:
            return "true lamps and windows (luminance > 1)";
        case TruthPart::ObservedLampsAndWindows:
            return "true observed lamps and windows";
        case TruthPart::UnobservedLampsAndWindows:
            return "true unobserved lamps and windows";
        case TruthPart::UnobservedLampsAndWindowsTurned30:
            return "true unobserved lamps and windows, turned 30 deg";
        case TruthPart::UnobservedLampsAndWindowsTurned60:
            return "true unobserved lamps and windows, turned 60 deg";
    }
    return "?";
}

double truthPartTurnDegrees(TruthPart part) {
    switch (part) {
        case TruthPart::UnobservedLampsAndWindowsTurned30:
            return 30.0;
        case TruthPart::UnobservedLampsAndWindowsTurned60:
            return 60.0;
        default:
            return 0.0;
    }
}

ImageRGB spliceTruth(const ImageRGB& prediction, const ImageRGB& truth, TruthPart part,
                     const std::vector<std::uint8_t>& observed) {
    const std::size_t pixels = std::size_t(truth.width) * std::size_t(truth.height);
    if (prediction.width != truth.width || prediction.height != truth.height)
        throw InputError("prediction is " + std::to_string(prediction.width) + "x" +
                         std::to_string(prediction.height) + " but the truth is " +
                         std::to_string(truth.width) + "x" + std::to_string(truth.height));
    if (observed.size() != pixels)
        throw InputError("observed mask has " + std::to_string(observed.size()) +
                         " pixels, the envmap " + std::to_string(pixels));
    // A turn of 360 degrees is the envmap's width in columns.
    const int width = truth.width;
    const int shift =
        width > 0 ? int(std::lround(truthPartTurnDegrees(part) / 360.0 * width)) % width : 0;
    ImageRGB out = prediction;
    for (std::size_t i = 0; i < pixels; ++i) {
        const float* t = &truth.pixels[3 * i];
        bool take = false;
        switch (part) {
            case TruthPart::Observed:
                take = observed[i] != 0;
                break;
            case TruthPart::Unobserved:
                take = observed[i] == 0;
                break;
            case TruthPart::LampsAndWindows:
                take = isLampOrWindow(t);
                break;
            case TruthPart::ObservedLampsAndWindows:
                take = observed[i] != 0 && isLampOrWindow(t);
                break;
            case TruthPart::UnobservedLampsAndWindows:
            case TruthPart::UnobservedLampsAndWindowsTurned30:
            case TruthPart::UnobservedLampsAndWindowsTurned60:
                take = observed[i] == 0 && isLampOrWindow(t);
                break;
        }
        if (!take) continue;
        const std::size_t row = i / std::size_t(width);
        const std::size_t column =
            (i % std::size_t(width) + std::size_t(shift)) % std::size_t(width);
        std::copy(t, t + 3, &out.pixels[3 * (row * std::size_t(width) + column)]);
    }
    return out;
}

}  // namespace lh
