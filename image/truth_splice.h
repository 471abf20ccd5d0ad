// Headroom of a predictor: its envmap with one part of the truth put in, so that the metrics
// say how much a perfect job on that part alone would gain. `lighthouse eval --headroom` scores
// five parts: the observed pixels (what a perfect MPI would give), the unobserved ones (a
// perfect completion), the lamps and windows (the pixels whose true luminance is above 1,
// where photos clip and which hold most of a room's light), the observed lamps and windows
// alone (how bright the MPI should make what the photo clipped), and the unobserved ones alone
// (the lamps and windows the completion has to invent).
#pragma once

#include "image/image.h"

#include <cstdint>
#include <vector>

namespace lh {

enum class TruthPart {
    Observed,
    Unobserved,
    LampsAndWindows,
    ObservedLampsAndWindows,
    UnobservedLampsAndWindows
};

// Every part, in the order the tables list them.
constexpr TruthPart kTruthParts[] = {TruthPart::Observed, TruthPart::Unobserved,
                                     TruthPart::LampsAndWindows, TruthPart::ObservedLampsAndWindows,
                                     TruthPart::UnobservedLampsAndWindows};

// A line for a table: "true observed pixels", ...
const char* truthPartName(TruthPart part);

// `prediction` with the pixels of `part` taken from `truth`. `observed` holds one byte per
// pixel (1 = observed; image/metrics.h loadMask), used by the observed and unobserved parts.
// Throws InputError if the sizes differ.
ImageRGB spliceTruth(const ImageRGB& prediction, const ImageRGB& truth, TruthPart part,
                     const std::vector<std::uint8_t>& observed);

}  // namespace lh
