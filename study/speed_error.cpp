#include "study/speed_error.h"

#include "core/atomic_file.h"
#include "core/errors.h"
#include "image/plot.h"
#include "render/free_space.h"
#include "sparsify/envmap_error.h"
#include "study/baseline_renderers.h"
#include "study/speed_summary.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

namespace lh {

std::string cellQuadratureLabel(int nodes, double bound, double threshold) {
    std::ostringstream s;
    s << nodes << " Gauss node" << (nodes > 1 ? "s" : "") << "/cell, bound " << bound << ", T<"
      << threshold;
    return s.str();
}

void SpeedErrorOptions::validate() const {
    if (!(referenceStep >= 0.005 && referenceStep <= 0.05)) {
        std::ostringstream s;
        s << "the reference step must be in [0.005, 0.05] voxels (default 0.05), got "
          << referenceStep;
        throw InputError(s.str());
    }
}

MarchOptions referenceMarchAt(double step) {
    MarchOptions march = MarchOptions::reference();
    const double scale = step / march.stepVoxels;  // the optical depth per step follows the step
    march.stepVoxels = step;
    march.maxStepOpticalDepth *= scale;
    return march;
}

namespace {

// "step 0.025, tau<0.01": a fixed-step setting without skipping (the reference's kind).
std::string referenceLabel(const MarchOptions& march) {
    std::ostringstream s;
    s << "step " << march.stepVoxels << ", tau<" << march.maxStepOpticalDepth;
    return s.str();
}

}  // namespace

std::vector<SpeedErrorRow> measureSpeedAgainstError(
    const LightingVolume& volume, const SpeedErrorOptions& o,
    const std::function<void(const std::string&)>& progress) {
    o.validate();
    const RenderVolume prepared(volume);
    const std::vector<Vec3d> points = freeSpacePoints(prepared, o.points, o.seed);
    const auto say = [&](const std::string& s) {
        if (progress) progress(s);
    };
    const MarchOptions referenceMarch = referenceMarchAt(o.referenceStep);
    say("reference envmaps (" + referenceLabel(referenceMarch) + ", no skipping)");
    std::vector<ImageRGB> reference;
    for (const Vec3d& p : points)
        reference.push_back(renderEnvmap(prepared, p, {o.width, o.height, referenceMarch}));

    // Every setting to measure, first collected, then timed in rounds.
    struct Trial {
        std::string method, setting;
        std::function<ImageRGB(const Vec3d&)> render;
    };
    std::vector<Trial> trials;
    const auto measure = [&](const std::string& method, const std::string& setting,
                             std::function<ImageRGB(const Vec3d&)> render) {
        if (o.methods.empty() ||
            std::find(o.methods.begin(), o.methods.end(), method) != o.methods.end())
            trials.push_back({method, setting, std::move(render)});
    };
    // How converged the reference is: the same at half the step and optical depth per step.
    const MarchOptions checkMarch = referenceMarchAt(o.referenceStep / 2);
    measure("reference-check", referenceLabel(checkMarch), [&](const Vec3d& p) {
        return renderEnvmap(prepared, p, {o.width, o.height, checkMarch});
    });
    for (double tauMax : {0.5, 0.1})
        for (double threshold : {1e-4, 1e-2})
            for (double step : {0.25, 0.5, 1.0, 2.0}) {
                std::ostringstream s;
                s << "step " << step << ", T<" << threshold << ", tau<" << tauMax;
                measure("ours-steps", s.str(), [&, step, threshold, tauMax](const Vec3d& p) {
                    return renderEnvmap(
                        prepared, p,
                        {o.width, o.height, MarchOptions{step, threshold, true, tauMax, 0}});
                });
            }
    // The termination threshold trades error for time too: a ray stops once what is left of
    // it (T) cannot add more than T x the radiance behind.
    for (double threshold : {1e-4, 1e-3, 1e-2})
        for (double bound : {0.25, 0.5, 1.0, 2.0, 3.0, 4.0, 8.0, 16.0, 64.0})
            for (int nodes : {1, 2, 3}) {
                MarchOptions march;
                march.cellRefineBound = bound;
                march.cellNodes = nodes;
                march.minTransmittance = threshold;
                measure("ours-cells", cellQuadratureLabel(nodes, bound, threshold),
                        [&, march](const Vec3d& p) {
                            return renderEnvmap(prepared, p, {o.width, o.height, march});
                        });
            }
    for (double step : {0.5, 1.0, 2.0})
        measure("openvdb-fixed-step", "step " + std::to_string(step).substr(0, 4),
                [&, step](const Vec3d& p) {
                    return renderEnvmapOpenVdbFixedStep(volume, p, o.width, o.height, step);
                });
    for (int spheres : {32, 64, 128, 256})
        measure("paper-spheres", std::to_string(spheres) + " spheres/level",
                [&, spheres](const Vec3d& p) {
                    return renderEnvmapConcentricSpheres(prepared, p, o.width, o.height, spheres);
                });

    // Round r renders every setting at every point once: a setting's time per point is the
    // fastest over the rounds, so each setting is sampled across the whole run and a drift of
    // the machine's speed (a shared machine's changes by up to 2x within an hour) falls on all of
    // them alike. The errors come from the first round (renders are deterministic).
    std::vector<SpeedErrorRow> rows(trials.size());
    std::vector<std::vector<double>> fastest(
        trials.size(), std::vector<double>(points.size(), std::numeric_limits<double>::infinity()));
    for (int round = 0; round < o.repeats; ++round) {
        for (std::size_t k = 0; k < trials.size(); ++k) {
            const Trial& trial = trials[k];
            const bool once = trial.method == "reference-check";  // 2 s an envmap: one round
            if (once && round > 0) continue;
            say("round " + std::to_string(round + 1) + "/" + std::to_string(o.repeats) + ": " +
                trial.method + ", " + trial.setting);
            std::vector<ImageRGB> images(points.size());
            for (std::size_t i = 0; i < points.size(); ++i) {
                const auto start = std::chrono::steady_clock::now();
                images[i] = trial.render(points[i]);
                fastest[k][i] =
                    std::min(fastest[k][i], std::chrono::duration<double, std::milli>(
                                                std::chrono::steady_clock::now() - start)
                                                .count());
            }
            if (round == 0) {
                const EnvmapSetError e =
                    compareEnvmapSets(images, reference);  // PSNR of identical images capped at 100
                rows[k] = {trial.method, trial.setting, 0.0, e.relativeRmse, e.psnr};
            }
        }
    }
    for (std::size_t k = 0; k < trials.size(); ++k) {
        double msSum = 0;  // sum over points of the fastest render
        for (double ms : fastest[k]) msSum += ms;
        rows[k].msPerEnvmap = msSum / points.size();
    }
    return rows;
}

namespace {

// Time against error, log-log, one series per method, each with a curve through its settings
// worth choosing (no other of its settings is both faster and more accurate).
std::string speedErrorSvg(const std::vector<SpeedErrorRow>& rows) {
    const std::map<std::string, std::string> colours = {{"ours-steps", "#d62728"},
                                                        {"ours-cells", "#9467bd"},
                                                        {"openvdb-fixed-step", "#1f77b4"},
                                                        {"paper-spheres", "#2ca02c"},
                                                        {"reference-check", "#7f7f7f"}};
    std::vector<PlotSeries> series;
    for (const auto& [method, colour] : colours) {
        PlotSeries sr{method, colour, {}, false, {}};
        for (const auto& r : rows)
            if (r.method == method)
                sr.points.push_back({r.msPerEnvmap, r.relativeRmse, r.method + ": " + r.setting});
        sr.curve = lowerLeftFront(sr.points);
        series.push_back(sr);
    }
    return svgPlot({"ms per 240x120 envmap (2 cores)", true, 10, 1e-3},
                   {"RMSE / mean radiance", true, 10, 1e-6}, series);
}

}  // namespace

void writeSpeedErrorReport(const std::vector<SpeedErrorRow>& rows, const std::string& directory,
                           int width, int height) {
    std::filesystem::create_directories(directory);
    std::ostringstream csv, md;
    csv << "method,setting,ms_per_envmap,envmaps_per_second,relative_rmse,psnr_db\n";
    md << "| method | setting | ms / envmap | envmaps / s | RMSE / mean radiance | PSNR (dB) "
          "|\n|---|---|---|---|---|---|\n";
    for (const auto& r : rows) {
        csv << r.method << "," << r.setting << "," << r.msPerEnvmap << "," << 1000 / r.msPerEnvmap
            << "," << r.relativeRmse << "," << r.psnr << "\n";
        char line[256];
        std::snprintf(line, sizeof line, "| %s | %s | %.1f | %.1f | %.2e | %.1f |\n",
                      r.method.c_str(), r.setting.c_str(), r.msPerEnvmap, 1000 / r.msPerEnvmap,
                      r.relativeRmse, r.psnr);
        md << line;
    }
    md << speedSummaryMarkdown(
        summarizeSpeedAgainstError(rows, SpeedSummary{}.errorBound, {}, width, height));
    const std::filesystem::path dir(directory);
    writeTextFile((dir / "speed_error.csv").string(), csv.str());
    writeTextFile((dir / "speed_error.md").string(), md.str());
    writeTextFile((dir / "speed_error.svg").string(), speedErrorSvg(rows));
}

}  // namespace lh
