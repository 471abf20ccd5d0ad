// What the speed targets ask of one speed-against-error run (study/speed_error.h): our
// fastest setting within an error bound, the default's standing, and, for every setting of the
// paper's method, our fastest setting at equal or lower error and how many times faster it is.
// Only rows of one run are compared: their times were taken on the same machine in the same
// rounds, so their ratios hold even when the machine's absolute speed drifts.
#pragma once

#include "study/speed_error.h"

#include <optional>
#include <string>
#include <vector>

namespace lh {

struct SpeedComparison {
    SpeedErrorRow theirs;               // a row of another method (e.g. the paper's spheres)
    std::optional<SpeedErrorRow> ours;  // our fastest row with error <= theirs (none: no such row)
    double speedup = 0;                 // their ms / our ms; 0 without `ours`
};

// The speed targets for 240x120 envmaps on this machine's 2 cores.
struct SpeedTargets {
    int width = 240, height = 120;                   // the envmap size they are set for
    double envmapsPerSecond = 100;                   // ... within the error bound
    std::string paperSetting = "128 spheres/level";  // the paper's own setting (640 spheres in all)
    double speedup = 20;                             // ... times faster, at equal or lower error
};

struct SpeedSummary {
    double errorBound = 1e-3;                         // RMSE / mean radiance
    std::optional<SpeedErrorRow> fastestWithinBound;  // our fastest row within errorBound
    std::optional<SpeedErrorRow> defaultSetting;      // the row of MarchOptions' defaults
    std::vector<SpeedComparison> againstPaper;        // one per "paper-spheres" row, in order
    SpeedTargets targets;
    int width = 240, height = 120;  // envmap size of the run: targets are judged only at theirs
    // The targets read from these rows: our fastest within errorBound renders at least
    // targets.envmapsPerSecond; against targets.paperSetting (when the run has it) our
    // fastest at equal or lower error is at least targets.speedup times faster. Both false
    // for a run at another envmap size (not judged).
    bool rateMet = false;
    std::optional<SpeedComparison> againstPaperSetting;
    bool speedupMet = false;
};

// Ours are the rows whose method starts with "ours-"; `width` x `height` is the size their
// envmaps were rendered at.
SpeedSummary summarizeSpeedAgainstError(const std::vector<SpeedErrorRow>& rows,
                                        double errorBound = 1e-3, const SpeedTargets& targets = {},
                                        int width = 240, int height = 120);

// The summary as Markdown: a list, a table, and the targets met or not, appended to
// speed_error.md.
std::string speedSummaryMarkdown(const SpeedSummary& summary);

}  // namespace lh
