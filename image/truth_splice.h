// Headroom of a predictor: its envmap with one part of the truth put in, so that the metrics
// say how much a perfect job on that part alone would gain. `lighthouse eval --headroom` scores
// these parts: the observed pixels (what a perfect MPI would give), the unobserved ones (a
// perfect completion), the lamps and windows (the pixels whose true luminance is above 1,
// where photos clip and which hold most of a room's light), the observed lamps and windows
// alone (how bright the MPI should make what the photo clipped), and the unobserved ones alone
// (the lamps and windows the completion has to invent). Two more rows put those unseen lamps and
// windows in at their true brightness but turned 30 and 60 degrees about the vertical axis: how
// near the truth the completion has to place a lamp before adding it helps.
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
    UnobservedLampsAndWindows,
    UnobservedLampsAndWindowsTurned30,
    UnobservedLampsAndWindowsTurned60
};

// Every part, in the order the tables list them.
constexpr TruthPart kTruthParts[] = {TruthPart::Observed,
                                     TruthPart::Unobserved,
                                     TruthPart::LampsAndWindows,
                                     TruthPart::ObservedLampsAndWindows,
                                     TruthPart::UnobservedLampsAndWindows,
                                     TruthPart::UnobservedLampsAndWindowsTurned30,
                                     TruthPart::UnobservedLampsAndWindowsTurned60};

// A line for a table: "true observed pixels", ...
const char* truthPartName(TruthPart part);

// How far a part's pixels are turned about the vertical axis (degrees, towards larger envmap
// columns, i.e. from +z towards +x); 0 for the parts that stay where they are.
double truthPartTurnDegrees(TruthPart part);

// `prediction` with the pixels of `part` taken from `truth`. `observed` holds one byte per
// pixel (1 = observed; image/metrics.h loadMask), used by the observed and unobserved parts.
// A turned part takes each true pixel of the part and writes it truthPartTurnDegrees to the
// side, rounded to whole columns, wrapping around; the pixels it came from keep the prediction.
// Throws InputError if the sizes differ.
ImageRGB spliceTruth(const ImageRGB& prediction, const ImageRGB& truth, TruthPart part,
                     const std::vector<std::uint8_t>& observed);

}  // namespace lh
