// What issue 7's speed targets ask of one speed-against-error run (render/speed_error.h): our
// fastest setting within an error bound, the default's standing, and, for every setting of the
// paper's method, our fastest setting at equal or lower error and how many times faster it is.
// Only rows of one run are compared: their times were taken on the same machine in the same
// rounds, so their ratios hold even when this VM's absolute speed drifts.
#pragma once

#include "render/speed_error.h"

#include <optional>
#include <string>
#include <vector>

namespace lh {

struct SpeedComparison {
    SpeedErrorRow theirs;               // a row of another method (e.g. the paper's spheres)
    std::optional<SpeedErrorRow> ours;  // our fastest row with error <= theirs (none: no such row)
    double speedup = 0;                 // their ms / our ms; 0 without `ours`
};

struct SpeedSummary {
    double errorBound = 1e-3;                       // RMSE / mean radiance
    std::optional<SpeedErrorRow> fastestWithinBound;  // our fastest row within errorBound
    std::optional<SpeedErrorRow> defaultSetting;      // the row of MarchOptions' defaults
    std::vector<SpeedComparison> againstPaper;        // one per "paper-spheres" row, in order
};

// Ours are the rows whose method starts with "ours-".
SpeedSummary summarizeSpeedAgainstError(const std::vector<SpeedErrorRow>& rows, double errorBound = 1e-3);

// The summary as Markdown: a list and a table, appended to speed_error.md.
std::string speedSummaryMarkdown(const SpeedSummary& summary);

}  // namespace lh
