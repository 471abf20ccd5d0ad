#include "render/speed_error.h"

#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/random.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "render/baseline_renderers.h"
#include "render/speed_summary.h"
#include "render/svg_plot.h"
#include "vdb/sparsity.h"
#include "vdb/volume_io.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <unistd.h>

namespace lh {

std::vector<Vec3d> freeSpacePoints(const RenderVolume& volume, int count, uint64_t seed) {
    if (volume.levels.empty()) throw InputError("volume has no levels");
    const RenderLevel& level = volume.levels[std::min<std::size_t>(1, volume.levels.size() - 1)];
    Random rng(seed);
    std::vector<Vec3d> points;
    // Candidates kept with their density: the fallback for fog needs the thinnest ones.
    std::vector<std::pair<float, Vec3d>> candidates;
    for (int tries = 0; tries < 100000 && int(points.size()) < count; ++tries) {
        Vec3d q;
        for (int a = 0; a < 3; ++a) q[a] = rng.uniform(level.domainLo[a], level.domainHi[a]);
        const Vec3d p = level.indexToWorld * (q - level.indexOffset);
        const float sigma = volume.sampleWorld(p).sigma;
        if (sigma == 0.f) points.push_back(p);
        else if (candidates.size() < std::size_t(64) * count) candidates.emplace_back(sigma, p);
    }
    if (int(points.size()) >= count) return points;
    // No (or too little) empty space: a predicted volume is dense low-alpha fog, every voxel
    // has a little density. A user queries in the air, not inside a wall, so take the
    // least dense of the first 64 x count candidates (deterministic for a seed).
    if (candidates.size() < std::size_t(count) - points.size())
        throw InputError("the volume has no empty space to put query points in, nor enough sampled points");
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; int(points.size()) < count; ++i) points.push_back(candidates[i].second);
    return points;
}

namespace {

struct ErrorStats {
    double psnr = 100, relativeRmse = 0;
};

ErrorStats compareSets(const std::vector<ImageRGB>& images, const std::vector<ImageRGB>& reference) {
    double squared = 0, mean = 0, psnrSum = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < images.size(); ++i) {
        for (std::size_t k = 0; k < images[i].pixels.size(); ++k) {
            squared += std::pow(double(images[i].pixels[k]) - reference[i].pixels[k], 2);
            mean += reference[i].pixels[k];
            ++n;
        }
        psnrSum += std::min(psnr(images[i], reference[i]), 100.0);
    }
    ErrorStats e;
    e.psnr = psnrSum / images.size();
    e.relativeRmse = mean > 0 ? std::sqrt(squared / n) / (mean / n) : 0.0;
    return e;
}

}  // namespace

std::string cellQuadratureLabel(int nodes, double bound, double threshold) {
    std::ostringstream s;
    s << nodes << " Gauss node" << (nodes > 1 ? "s" : "") << "/cell, bound " << bound << ", T<" << threshold;
    return s.str();
}

std::vector<SpeedErrorRow> measureSpeedAgainstError(const LightingVolume& volume, const SpeedErrorOptions& o,
                                                    const std::function<void(const std::string&)>& progress) {
    const RenderVolume prepared(volume);
    const std::vector<Vec3d> points = freeSpacePoints(prepared, o.points, o.seed);
    const auto say = [&](const std::string& s) { if (progress) progress(s); };
    say("reference envmaps (0.05-voxel steps, no skipping)");
    std::vector<ImageRGB> reference;
    for (const Vec3d& p : points) reference.push_back(renderEnvmap(prepared, p, {o.width, o.height, MarchOptions::reference()}));

    // Every setting to measure, first collected, then timed in rounds.
    struct Trial {
        std::string method, setting;
        std::function<ImageRGB(const Vec3d&)> render;
    };
    std::vector<Trial> trials;
    const auto measure = [&](const std::string& method, const std::string& setting,
                             std::function<ImageRGB(const Vec3d&)> render) {
        if (o.methods.empty() || std::find(o.methods.begin(), o.methods.end(), method) != o.methods.end())
            trials.push_back({method, setting, std::move(render)});
    };
    // How converged the reference is: the same at half the step and optical depth per step.
    measure("reference-check", "step 0.025, tau<0.01", [&](const Vec3d& p) {
        return renderEnvmap(prepared, p, {o.width, o.height, MarchOptions{0.025, 0.0, false, 0.01, 0}});
    });
    for (double tauMax : {0.5, 0.1})
        for (double threshold : {1e-4, 1e-2})
            for (double step : {0.25, 0.5, 1.0, 2.0}) {
                std::ostringstream s;
                s << "step " << step << ", T<" << threshold << ", tau<" << tauMax;
                measure("ours-steps", s.str(), [&, step, threshold, tauMax](const Vec3d& p) {
                    return renderEnvmap(prepared, p, {o.width, o.height, MarchOptions{step, threshold, true, tauMax, 0}});
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
                        [&, march](const Vec3d& p) { return renderEnvmap(prepared, p, {o.width, o.height, march}); });
            }
    for (double step : {0.5, 1.0, 2.0})
        measure("openvdb-fixed-step", "step " + std::to_string(step).substr(0, 4),
                [&, step](const Vec3d& p) { return renderEnvmapOpenVdbFixedStep(volume, p, o.width, o.height, step); });
    for (int spheres : {32, 64, 128, 256})
        measure("paper-spheres", std::to_string(spheres) + " spheres/level",
                [&, spheres](const Vec3d& p) { return renderEnvmapConcentricSpheres(prepared, p, o.width, o.height, spheres); });

    // Round r renders every setting at every point once: a setting's time per point is the
    // fastest over the rounds, so each setting is sampled across the whole run and a drift of
    // the machine's speed (a shared machine's changes by up to 2x within an hour) falls on all of them
    // alike. The errors come from the first round (renders are deterministic).
    std::vector<SpeedErrorRow> rows(trials.size());
    std::vector<std::vector<double>> fastest(trials.size(),
                                             std::vector<double>(points.size(), std::numeric_limits<double>::infinity()));
    for (int round = 0; round < o.repeats; ++round) {
        for (std::size_t k = 0; k < trials.size(); ++k) {
            const Trial& trial = trials[k];
            const bool once = trial.method == "reference-check";  // 2 s an envmap: one round
            if (once && round > 0) continue;
            say("round " + std::to_string(round + 1) + "/" + std::to_string(o.repeats) + ": " + trial.method + ", " +
                trial.setting);
            std::vector<ImageRGB> images(points.size());
            for (std::size_t i = 0; i < points.size(); ++i) {
                const auto start = std::chrono::steady_clock::now();
                images[i] = trial.render(points[i]);
                fastest[k][i] = std::min(
                    fastest[k][i], std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
            }
            if (round == 0) {
                const ErrorStats e = compareSets(images, reference);  // PSNR of identical images capped at 100
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
    const std::map<std::string, std::string> colours = {
        {"ours-steps", "#d62728"}, {"ours-cells", "#9467bd"}, {"openvdb-fixed-step", "#1f77b4"},
        {"paper-spheres", "#2ca02c"}, {"reference-check", "#7f7f7f"}};
    std::vector<PlotSeries> series;
    for (const auto& [method, colour] : colours) {
        PlotSeries sr{method, colour, {}, false, {}};
        for (const auto& r : rows)
            if (r.method == method) sr.points.push_back({r.msPerEnvmap, r.relativeRmse, r.method + ": " + r.setting});
        sr.curve = lowerLeftFront(sr.points);
        series.push_back(sr);
    }
    return svgPlot({"ms per 240x120 envmap (2 cores)", true, 10, 1e-3},
                   {"RMSE / mean radiance", true, 10, 1e-6}, series);
}

}  // namespace

void writeSpeedErrorReport(const std::vector<SpeedErrorRow>& rows, const std::string& directory, int width,
                           int height) {
    std::filesystem::create_directories(directory);
    std::ostringstream csv, md;
    csv << "method,setting,ms_per_envmap,envmaps_per_second,relative_rmse,psnr_db\n";
    md << "| method | setting | ms / envmap | envmaps / s | RMSE / mean radiance | PSNR (dB) |\n|---|---|---|---|---|---|\n";
    for (const auto& r : rows) {
        csv << r.method << "," << r.setting << "," << r.msPerEnvmap << "," << 1000 / r.msPerEnvmap << ","
            << r.relativeRmse << "," << r.psnr << "\n";
        char line[256];
        std::snprintf(line, sizeof line, "| %s | %s | %.1f | %.1f | %.2e | %.1f |\n", r.method.c_str(),
                      r.setting.c_str(), r.msPerEnvmap, 1000 / r.msPerEnvmap, r.relativeRmse, r.psnr);
        md << line;
    }
    md << speedSummaryMarkdown(summarizeSpeedAgainstError(rows, SpeedSummary{}.errorBound, {}, width, height));
    const std::filesystem::path dir(directory);
    writeTextFile((dir / "speed_error.csv").string(), csv.str());
    writeTextFile((dir / "speed_error.md").string(), md.str());
    writeTextFile((dir / "speed_error.svg").string(), speedErrorSvg(rows));
}

// ---- Memory against error ----

namespace {

std::vector<ImageRGB> renderAll(const RenderVolume& volume, const std::vector<Vec3d>& points, int w, int h,
                                double* msPerEnvmap = nullptr, const MarchOptions& march = {}) {
    std::vector<ImageRGB> images;
    const auto start = std::chrono::steady_clock::now();
    for (const Vec3d& p : points) images.push_back(renderEnvmap(volume, p, {w, h, march}));
    if (msPerEnvmap)
        *msPerEnvmap = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
                       std::max<std::size_t>(1, points.size());
    return images;
}

uint64_t fileBytes(const std::string& path) { return std::filesystem::file_size(path); }

std::string scratchDirectory(const MemoryErrorOptions& o) {
    const std::filesystem::path dir = o.scratchDir.empty()
                                          ? std::filesystem::temp_directory_path() /
                                                ("lighthouse_sparsity_" + std::to_string(::getpid()))
                                          : std::filesystem::path(o.scratchDir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

// The volume as stored: through a half-precision file and back when asked.
LightingVolume asStored(const LightingVolume& volume, bool half, const std::string& scratch, uint64_t* bytes) {
    const std::string path = scratch + (half ? "/half.vdb" : "/float.vdb");
    saveSparseVolume(path, volume, half);
    if (bytes) *bytes = fileBytes(path);
    LightingVolume loaded = loadVolume(path);
    std::filesystem::remove(path);
    return loaded;
}

}  // namespace

double requiredPsnrForLoss(double lossDb, double basePsnr) {
    if (!(lossDb > 0 && std::isfinite(lossDb) && std::isfinite(basePsnr)))
        throw InputError("a PSNR loss target must be positive, got " + std::to_string(lossDb));
    return basePsnr - 20.0 * std::log10(std::pow(10.0, lossDb / 20.0) - 1.0);
}

std::vector<MemoryErrorRow> measureMemoryAgainstError(const LightingVolume& volume, const MemoryErrorOptions& o,
                                                      const std::function<void(const std::string&)>& progress) {
    const auto say = [&](const std::string& s) { if (progress) progress(s); };
    const RenderVolume unprunedRender(volume);
    const std::vector<Vec3d> points = freeSpacePoints(unprunedRender, o.points, o.seed);
    const std::vector<ImageRGB> reference = renderAll(unprunedRender, points, o.width, o.height, nullptr, o.errorMarch);
    // Ground truth: the data set's envmaps at their own points.
    std::vector<Vec3d> gtPoints;
    std::vector<ImageRGB> gt;
    if (!o.datasetDir.empty()) {
        const CamerasFile cameras = loadCamerasFile(o.datasetDir + "/cameras.json");
        for (const auto& e : cameras.envmaps) {
            gt.push_back(readImage(o.datasetDir + "/" + e.file));
            gtPoints.push_back(e.position);
        }
        if (gt.empty()) throw InputError(o.datasetDir + "/cameras.json lists no envmaps");
    }
    const auto gtPsnr = [&](const RenderVolume& v) {
        double sum = 0;
        for (std::size_t i = 0; i < gt.size(); ++i)
            sum += psnr(renderEnvmap(v, gtPoints[i], {gt[i].width, gt[i].height, o.errorMarch}), gt[i]);
        return sum / std::max<std::size_t>(1, gt.size());
    };
    const std::string scratch = scratchDirectory(o);
    std::vector<MemoryErrorRow> rows;
    const auto addRow = [&](const std::string& setting, double tau, const LightingVolume& v) {
        say(setting);
        MemoryErrorRow row;
        row.setting = setting;
        row.tau = tau;
        row.activeVoxels = activeDensityVoxels(v);
        row.memoryBytes = v.memoryBytes();
        row.levels = int(v.levels.size());
        asStored(v, false, scratch, &row.diskBytesFloat);
        const LightingVolume stored = asStored(v, true, scratch, &row.diskBytesHalf);
        const RenderVolume render(o.halfPrecision ? stored : v);
        renderAll(render, points, o.width, o.height);  // warm caches before timing
        renderAll(render, points, o.width, o.height, &row.msPerEnvmap);
        const ErrorStats e = compareSets(renderAll(render, points, o.width, o.height, nullptr, o.errorMarch), reference);
        row.psnrVsUnpruned = tau < 0 ? 100.0 : e.psnr;
        row.relativeRmse = tau < 0 ? 0.0 : e.relativeRmse;
        if (!gt.empty()) {
            row.psnrGroundTruth = gtPsnr(render);
            row.lossDb = rows.empty() ? 0.0 : rows.front().psnrGroundTruth - row.psnrGroundTruth;
        }
        rows.push_back(row);
    };
    // The unpruned row is measured in float: it is the volume as given.
    {
        say("unpruned");
        MemoryErrorRow row;
        row.setting = "unpruned";
        row.tau = -1;
        row.activeVoxels = activeDensityVoxels(volume);
        row.memoryBytes = volume.memoryBytes();
        row.levels = int(volume.levels.size());
        asStored(volume, false, scratch, &row.diskBytesFloat);
        asStored(volume, true, scratch, &row.diskBytesHalf);
        renderAll(unprunedRender, points, o.width, o.height);
        renderAll(unprunedRender, points, o.width, o.height, &row.msPerEnvmap);
        if (!gt.empty()) row.psnrGroundTruth = gtPsnr(unprunedRender);
        rows.push_back(row);
    }
    for (double tau : o.taus) {
        SparsityOptions so;
        so.tau = tau;
        std::ostringstream name;
        name << "tau " << tau;
        addRow(name.str(), tau, sparsify(volume, so));
    }
    std::filesystem::remove_all(scratch);
    return rows;
}

BoundChoice chooseSparsityBound(const LightingVolume& volume, double requiredPsnr, const MemoryErrorOptions& o,
                                const std::function<void(const std::string&)>& progress) {
    const RenderVolume unprunedRender(volume);
    const std::vector<Vec3d> points = freeSpacePoints(unprunedRender, o.points, o.seed);
    const std::vector<ImageRGB> reference = renderAll(unprunedRender, points, o.width, o.height, nullptr, o.errorMarch);
    const std::string scratch = scratchDirectory(o);
    BoundChoice choice;
    for (double tau = 0.1; tau > 0.9e-6; tau /= std::sqrt(10.0)) {
        SparsityOptions so;
        so.tau = tau;
        const LightingVolume pruned = sparsify(volume, so);
        const RenderVolume render(o.halfPrecision ? asStored(pruned, true, scratch, nullptr) : pruned);
        const ErrorStats e = compareSets(renderAll(render, points, o.width, o.height, nullptr, o.errorMarch), reference);
        if (progress) {
            char line[128];
            std::snprintf(line, sizeof line, "tau %.3g: %.1f dB against the unpruned envmaps", tau, e.psnr);
            progress(line);
        }
        if (e.psnr >= requiredPsnr) {
            choice = {tau, e.psnr};
            break;
        }
    }
    std::filesystem::remove_all(scratch);
    return choice;
}

namespace {

// Bytes (log) against PSNR vs the unpruned envmaps (linear, 100 = identical), in memory and
// on disk, with the target (a tenth of dense storage) marked.
std::string memorySvg(const std::vector<MemoryErrorRow>& rows, double denseBytes) {
    PlotSeries memory{"in memory", "#d62728", {}, true, {}}, disk{"on disk (Blosc, half)", "#1f77b4", {}, true, {}};
    for (const auto& r : rows) {
        memory.points.push_back({double(r.memoryBytes), r.psnrVsUnpruned, r.setting});
        disk.points.push_back({double(r.diskBytesHalf), r.psnrVsUnpruned, r.setting});
    }
    return svgPlot({"bytes", true, 10, 1.0}, {"PSNR vs unpruned envmaps (dB, 100 = identical)", false, 10, 0},
                   {memory, disk}, {{denseBytes * kMemoryTargetFraction, "dense / 10"}});
}

}  // namespace

std::string memoryTargetMarkdown(const std::vector<MemoryErrorRow>& rows, double denseBytes, double tau) {
    const auto row = std::find_if(rows.begin(), rows.end(), [&](const MemoryErrorRow& r) { return r.tau == tau; });
    std::ostringstream md;
    char line[512];
    std::snprintf(line, sizeof line,
                  "\n## Against the target, at the default bound tau %g\n\n"
                  "At most a tenth of the dense float storage (%.3g MB: sigma and RGB as floats at every voxel of "
                  "every level) with at most %.1f dB PSNR lost on envmaps:\n\n",
                  tau, denseBytes / 1e6, kMemoryTargetLossDb);
    md << line;
    if (row == rows.end()) {
        md << "* not measured: this run has no row at that bound\n";
        return md.str();
    }
    const char* verdict[2] = {"**not met**", "**met**"};
    const auto share = [&](const char* what, uint64_t bytes) {
        const double fraction = bytes / denseBytes;
        std::snprintf(line, sizeof line, "* %s: %.3g MB, %.1f%% of dense: %s\n", what, bytes / 1e6, 100 * fraction,
                      verdict[fraction <= kMemoryTargetFraction]);
        md << line;
    };
    share("on disk (Blosc, half precision)", row->diskBytesHalf);
    share("in memory (OpenVDB grids)", row->memoryBytes);
    if (row->psnrGroundTruth >= 0)
        std::snprintf(line, sizeof line, "* PSNR against ground truth %.3f dB, %.3f dB lost: %s\n", row->psnrGroundTruth,
                      std::max(row->lossDb, 0.0), verdict[row->lossDb <= kMemoryTargetLossDb]);  // a gain is no loss
    else
        std::snprintf(line, sizeof line,
                      "* PSNR lost: not measured without ground truth (--dataset); %.1f dB against the unpruned "
                      "envmaps\n",
                      row->psnrVsUnpruned);
    md << line;
    return md.str();
}

void writeMemoryErrorReport(const std::vector<MemoryErrorRow>& rows, const std::string& directory, double denseBytes) {
    std::filesystem::create_directories(directory);
    std::ostringstream csv, md;
    const bool gt = !rows.empty() && rows.front().psnrGroundTruth >= 0;
    csv << "setting,tau,levels,active_voxels,memory_bytes,disk_bytes_float,disk_bytes_half,fraction_of_dense,"
           "psnr_vs_unpruned_db,relative_rmse,ms_per_envmap,psnr_ground_truth_db,loss_db\n";
    md << "| setting | levels | active voxels | MB in memory | MB on disk (float) | MB on disk (half) | memory / dense | "
          "PSNR vs unpruned (dB) | RMSE / mean | ms / envmap |"
       << (gt ? " PSNR vs ground truth (dB) | loss (dB) |" : "") << "\n|---|---|---|---|---|---|---|---|---|---|"
       << (gt ? "---|---|" : "") << "\n";
    for (const auto& r : rows) {
        csv << r.setting << "," << r.tau << "," << r.levels << "," << r.activeVoxels << "," << r.memoryBytes << ","
            << r.diskBytesFloat << "," << r.diskBytesHalf << "," << r.memoryBytes / denseBytes << "," << r.psnrVsUnpruned
            << "," << r.relativeRmse << "," << r.msPerEnvmap << "," << r.psnrGroundTruth << "," << r.lossDb << "\n";
        char line[512];
        std::snprintf(line, sizeof line, "| %s | %d | %llu | %.2f | %.3f | %.3f | %.3f | %.1f | %.1e | %.1f |",
                      r.setting.c_str(), r.levels, static_cast<unsigned long long>(r.activeVoxels), r.memoryBytes / 1e6,
                      r.diskBytesFloat / 1e6, r.diskBytesHalf / 1e6, r.memoryBytes / denseBytes, r.psnrVsUnpruned,
                      r.relativeRmse, r.msPerEnvmap);
        md << line;
        if (gt) {
            // A loss that rounds to zero prints as 0.000, not -0.000.
            std::snprintf(line, sizeof line, " %.3f | %.3f |", r.psnrGroundTruth, std::abs(r.lossDb) < 5e-4 ? 0.0 : r.lossDb);
            md << line;
        }
        md << "\n";
    }
    md << memoryTargetMarkdown(rows, denseBytes, SparsityOptions{}.tau);
    const std::filesystem::path dir(directory);
    writeTextFile((dir / "memory_error.csv").string(), csv.str());
    writeTextFile((dir / "memory_error.md").string(), md.str());
    writeTextFile((dir / "memory_error.svg").string(), memorySvg(rows, denseBytes));
}

}  // namespace lh
