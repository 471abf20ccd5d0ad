#include "study/memory_error.h"

#include "core/atomic_file.h"
#include "core/camera.h"
#include "core/dataset_files.h"
#include "core/errors.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "image/plot.h"
#include "render/envmap.h"
#include "render/free_space.h"
#include "sparsify/envmap_error.h"
#include "vdb/sparsity.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace lh {

std::vector<MemoryErrorRow> measureMemoryAgainstError(
    const LightingVolume& volume, const MemoryErrorOptions& o,
    const std::function<void(const std::string&)>& progress) {
    const auto say = [&](const std::string& s) {
        if (progress) progress(s);
    };
    const RenderVolume unprunedRender(volume);
    const std::vector<Vec3d> points = freeSpacePoints(unprunedRender, o.points, o.seed);
    const std::vector<ImageRGB> reference =
        renderEnvmapsAt(unprunedRender, points, o.width, o.height, nullptr, o.errorMarch);
    // Ground truth: the data set's envmaps at their own points.
    std::vector<Vec3d> gtPoints;
    std::vector<ImageRGB> gt;
    if (!o.datasetDir.empty()) {
        const CamerasFile cameras = loadCamerasFile(o.datasetDir + "/" + dataset::kCameras);
        for (const auto& e : cameras.envmaps) {
            gt.push_back(readImage(o.datasetDir + "/" + e.file));
            gtPoints.push_back(e.position);
        }
        if (gt.empty())
            throw InputError(o.datasetDir + "/" + dataset::kCameras + " lists no envmaps");
    }
    const auto gtPsnr = [&](const RenderVolume& v) {
        double sum = 0;
        for (std::size_t i = 0; i < gt.size(); ++i)
            sum += psnr(renderEnvmap(v, gtPoints[i], {gt[i].width, gt[i].height, o.errorMarch}),
                        gt[i]);
        return sum / std::max<std::size_t>(1, gt.size());
    };
    const std::string scratch = scratchDirectory(o.scratchDir);
    std::vector<MemoryErrorRow> rows;
    // A row's setting, its size in memory and its sizes on disk (float, half and, when asked,
    // rounded); returns the volume read back from the file a pruned row renders: the rounded
    // one when asked, else the half one.
    const auto describe = [&](MemoryErrorRow& row, const std::string& setting, double tau,
                              const LightingVolume& v) {
        say(setting);
        row.setting = setting;
        row.tau = tau;
        row.activeVoxels = activeDensityVoxels(v);
        row.memoryBytes = v.memoryBytes();
        row.levels = int(v.levels.size());
        asStored(v, false, scratch, &row.diskBytesFloat);
        LightingVolume stored = asStored(v, true, scratch, &row.diskBytesHalf);
        if (o.mantissaBits > 0) {
            row.mantissaBits = o.mantissaBits;
            stored = asStored(v, false, scratch, &row.diskBytesRounded, o.mantissaBits);
        }
        return stored;
    };
    const auto addRow = [&](const std::string& setting, double tau, const LightingVolume& v) {
        MemoryErrorRow row;
        const LightingVolume stored = describe(row, setting, tau, v);
        const RenderVolume render(o.halfPrecision || o.mantissaBits > 0 ? stored : v);
        renderEnvmapsAt(render, points, o.width, o.height);  // warm caches before timing
        renderEnvmapsAt(render, points, o.width, o.height, &row.msPerEnvmap);
        const EnvmapSetError e = compareEnvmapSets(
            renderEnvmapsAt(render, points, o.width, o.height, nullptr, o.errorMarch), reference);
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
        MemoryErrorRow row;
        describe(row, "unpruned", -1, volume);
        renderEnvmapsAt(unprunedRender, points, o.width, o.height);
        renderEnvmapsAt(unprunedRender, points, o.width, o.height, &row.msPerEnvmap);
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

namespace {

// The mantissa bits of the rounded files the rows measured (0: none were measured).
int roundedBits(const std::vector<MemoryErrorRow>& rows) {
    return rows.empty() ? 0 : rows.front().mantissaBits;
}

// Bytes (log) against PSNR vs the unpruned envmaps (linear, 100 = identical), in memory and
// on disk, with the target (a tenth of dense storage) marked.
std::string memorySvg(const std::vector<MemoryErrorRow>& rows, double denseBytes) {
    const int bits = roundedBits(rows);
    PlotSeries memory{"in memory", "#d62728", {}, true, {}},
        disk{bits > 0 ? "on disk (Blosc, " + std::to_string(bits) + "-bit mantissas)"
                      : std::string("on disk (Blosc, half)"),
             "#1f77b4",
             {},
             true,
             {}};
    for (const auto& r : rows) {
        memory.points.push_back({double(r.memoryBytes), r.psnrVsUnpruned, r.setting});
        disk.points.push_back(
            {double(bits > 0 ? r.diskBytesRounded : r.diskBytesHalf), r.psnrVsUnpruned, r.setting});
    }
    return svgPlot({"bytes", true, 10, 1.0},
                   {"PSNR vs unpruned envmaps (dB, 100 = identical)", false, 10, 0}, {memory, disk},
                   {{denseBytes * kMemoryTargetFraction, "dense / 10"}});
}

}  // namespace

std::string memoryTargetMarkdown(const std::vector<MemoryErrorRow>& rows, double denseBytes,
                                 double tau) {
    const auto row = std::find_if(rows.begin(), rows.end(),
                                  [&](const MemoryErrorRow& r) { return r.tau == tau; });
    std::ostringstream md;
    char line[512];
    std::snprintf(line, sizeof line,
                  "\n## Against the target, at the default bound tau %g\n\n"
                  "At most a tenth of the dense float storage (%.3g MB: sigma and RGB as floats at "
                  "every voxel of "
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
        std::snprintf(line, sizeof line, "* %s: %.3g MB, %.1f%% of dense: %s\n", what, bytes / 1e6,
                      100 * fraction, verdict[fraction <= kMemoryTargetFraction]);
        md << line;
    };
    if (row->mantissaBits > 0)
        share(("on disk (Blosc, floats rounded to " + std::to_string(row->mantissaBits) +
               " mantissa bits)")
                  .c_str(),
              row->diskBytesRounded);
    else
        share("on disk (Blosc, half precision)", row->diskBytesHalf);
    share("in memory (OpenVDB grids)", row->memoryBytes);
    if (row->psnrGroundTruth >= 0)
        std::snprintf(line, sizeof line, "* PSNR against ground truth %.3f dB, %.3f dB lost: %s\n",
                      row->psnrGroundTruth, std::max(row->lossDb, 0.0),
                      verdict[row->lossDb <= kMemoryTargetLossDb]);  // a gain is no loss
    else
        std::snprintf(line, sizeof line,
                      "* PSNR lost: not measured without ground truth (--dataset); %.1f dB against "
                      "the unpruned "
                      "envmaps\n",
                      row->psnrVsUnpruned);
    md << line;
    return md.str();
}

void writeMemoryErrorReport(const std::vector<MemoryErrorRow>& rows, const std::string& directory,
                            double denseBytes) {
    std::filesystem::create_directories(directory);
    std::ostringstream csv, md;
    const bool gt = !rows.empty() && rows.front().psnrGroundTruth >= 0;
    const int bits = roundedBits(rows);
    csv << "setting,tau,levels,active_voxels,memory_bytes,disk_bytes_float,disk_bytes_half,"
           "fraction_of_dense,"
           "psnr_vs_unpruned_db,relative_rmse,ms_per_envmap,psnr_ground_truth_db,loss_db,"
           "mantissa_bits,disk_bytes_rounded\n";
    md << "| setting | levels | active voxels | MB in memory | MB on disk (float) | MB on disk "
          "(half) |"
       << (bits > 0 ? " MB on disk (" + std::to_string(bits) + "-bit mantissas) |" : "")
       << " memory / dense | PSNR vs unpruned (dB) | RMSE / mean | ms / envmap |"
       << (gt ? " PSNR vs ground truth (dB) | loss (dB) |" : "")
       << "\n|---|---|---|---|---|---|---|---|---|---|" << (bits > 0 ? "---|" : "")
       << (gt ? "---|---|" : "") << "\n";
    for (const auto& r : rows) {
        csv << r.setting << "," << r.tau << "," << r.levels << "," << r.activeVoxels << ","
            << r.memoryBytes << "," << r.diskBytesFloat << "," << r.diskBytesHalf << ","
            << r.memoryBytes / denseBytes << "," << r.psnrVsUnpruned << "," << r.relativeRmse << ","
            << r.msPerEnvmap << "," << r.psnrGroundTruth << "," << r.lossDb << "," << r.mantissaBits
            << "," << r.diskBytesRounded << "\n";
        char line[512];
        std::snprintf(line, sizeof line, "| %s | %d | %llu | %.2f | %.3f | %.3f |",
                      r.setting.c_str(), r.levels, static_cast<unsigned long long>(r.activeVoxels),
                      r.memoryBytes / 1e6, r.diskBytesFloat / 1e6, r.diskBytesHalf / 1e6);
        md << line;
        if (bits > 0) {
            std::snprintf(line, sizeof line, " %.3f |", r.diskBytesRounded / 1e6);
            md << line;
        }
        std::snprintf(line, sizeof line, " %.3f | %.1f | %.1e | %.1f |", r.memoryBytes / denseBytes,
                      r.psnrVsUnpruned, r.relativeRmse, r.msPerEnvmap);
        md << line;
        if (gt) {
            // A loss that rounds to zero prints as 0.000, not -0.000.
            std::snprintf(line, sizeof line, " %.3f | %.3f |", r.psnrGroundTruth,
                          std::abs(r.lossDb) < 5e-4 ? 0.0 : r.lossDb);
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
