#include "study/speed_summary.h"

#include "render/ray_marcher.h"

#include <cstdio>
#include <sstream>

namespace lh {

namespace {

bool isOurs(const SpeedErrorRow& r) { return r.method.rfind("ours-", 0) == 0; }

// Our fastest row with relative RMSE <= bound.
std::optional<SpeedErrorRow> fastestOursWithin(const std::vector<SpeedErrorRow>& rows,
                                               double bound) {
    std::optional<SpeedErrorRow> best;
    for (const SpeedErrorRow& r : rows)
        if (isOurs(r) && r.relativeRmse <= bound && (!best || r.msPerEnvmap < best->msPerEnvmap))
            best = r;
    return best;
}

std::string describe(const SpeedErrorRow& r) {
    char text[256];
    std::snprintf(text, sizeof text, "%s, %s: %.3g ms (%.3g envmaps/s) at %.2e", r.method.c_str(),
                  r.setting.c_str(), r.msPerEnvmap, 1000 / r.msPerEnvmap, r.relativeRmse);
    return text;
}

}  // namespace

SpeedSummary summarizeSpeedAgainstError(const std::vector<SpeedErrorRow>& rows, double errorBound,
                                        const SpeedTargets& targets, int width, int height) {
    SpeedSummary s;
    s.errorBound = errorBound;
    s.targets = targets;
    s.width = width, s.height = height;
    s.fastestWithinBound = fastestOursWithin(rows, errorBound);
    const MarchOptions defaults;
    const std::string defaultLabel = cellQuadratureLabel(
        defaults.cellNodes, defaults.cellRefineBound, defaults.minTransmittance);
    for (const SpeedErrorRow& r : rows) {
        if (r.method == "ours-cells" && r.setting == defaultLabel) s.defaultSetting = r;
        if (r.method != "paper-spheres") continue;
        SpeedComparison c{r, fastestOursWithin(rows, r.relativeRmse), 0.0};
        if (c.ours) c.speedup = r.msPerEnvmap / c.ours->msPerEnvmap;
        s.againstPaper.push_back(c);
        if (r.setting == targets.paperSetting) s.againstPaperSetting = c;
    }
    const bool judged = width == targets.width && height == targets.height;
    s.rateMet = judged && s.fastestWithinBound &&
                1000 / s.fastestWithinBound->msPerEnvmap >= targets.envmapsPerSecond;
    s.speedupMet =
        judged && s.againstPaperSetting && s.againstPaperSetting->speedup >= targets.speedup;
    return s;
}

std::string speedSummaryMarkdown(const SpeedSummary& s) {
    std::ostringstream md;
    char bound[32], line[512];
    std::snprintf(bound, sizeof bound, "%.0e", s.errorBound);
    md << "\n## Against the targets (rows of this run)\n\n";
    md << "* fastest within RMSE <= " << bound << " of the mean radiance: "
       << (s.fastestWithinBound ? describe(*s.fastestWithinBound)
                                : std::string("no setting of ours is that close"))
       << "\n";
    if (s.defaultSetting) md << "* the default: " << describe(*s.defaultSetting) << "\n";
    if (!s.againstPaper.empty()) {
        md << "\nThe paper's method against our fastest setting at equal or lower error:\n\n"
           << "| paper's method | its ms | its error | our fastest at equal or lower error | our "
              "ms | our error | times faster |\n"
           << "|---|---|---|---|---|---|---|\n";
        for (const SpeedComparison& c : s.againstPaper) {
            if (c.ours)
                std::snprintf(line, sizeof line,
                              "| %s | %.3g | %.2e | %s, %s | %.3g | %.2e | %.1f |\n",
                              c.theirs.setting.c_str(), c.theirs.msPerEnvmap, c.theirs.relativeRmse,
                              c.ours->method.c_str(), c.ours->setting.c_str(), c.ours->msPerEnvmap,
                              c.ours->relativeRmse, c.speedup);
            else
                std::snprintf(line, sizeof line, "| %s | %.3g | %.2e | none | | | |\n",
                              c.theirs.setting.c_str(), c.theirs.msPerEnvmap,
                              c.theirs.relativeRmse);
            md << line;
        }
    }
    const SpeedTargets& t = s.targets;
    const char* verdict[2] = {"**not met**", "**met**"};
    std::snprintf(line, sizeof line, "\nTargets (%dx%d envmaps, 2 cores):\n\n", t.width, t.height);
    md << line;
    if (s.width != t.width || s.height != t.height) {
        std::snprintf(line, sizeof line, "* not judged: this run rendered %dx%d envmaps\n", s.width,
                      s.height);
        md << line;
        return md.str();
    }
    std::snprintf(line, sizeof line, "* >= %g envmaps/s within RMSE %s: %s", t.envmapsPerSecond,
                  bound, verdict[s.rateMet]);
    md << line;
    if (s.fastestWithinBound) {
        std::snprintf(line, sizeof line, " (%.0f/s)", 1000 / s.fastestWithinBound->msPerEnvmap);
        md << line;
    }
    std::snprintf(line, sizeof line,
                  "\n* >= %gx faster than the paper's %s at equal or lower error: ", t.speedup,
                  t.paperSetting.c_str());
    md << line;
    if (s.againstPaperSetting) {
        std::snprintf(line, sizeof line, "%s (%.1fx)\n", verdict[s.speedupMet],
                      s.againstPaperSetting->speedup);
        md << line;
    } else {
        md << "not measured in this run\n";
    }
    return md.str();
}

}  // namespace lh
