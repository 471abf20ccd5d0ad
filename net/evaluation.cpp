#include "net/evaluation.h"

#include "net/eval_table.h"

#include "core/atomic_file.h"
#include "core/dataset_files.h"
#include "core/errors.h"
#include "image/contact_sheet.h"
#include "image/highlights.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "image/resample.h"
#include "image/truth_splice.h"
#include "net/predictor.h"
#include "net/training_data.h"
#include "render/envmap.h"
#include "render/render_volume.h"
#include "synth/oracle.h"
#include "synth/panorama.h"
#include "synth/radiance_field.h"
#include "synth/ray_tracer.h"
#include "synth/scene_json.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace fs = std::filesystem;

namespace lh::net {

namespace {

// sRGB 0.5 grey, in linear radiance.
constexpr float kGreyFill = 0.2140411f;

// Envmap at `position` with whatever the volume leaves unseen (its transmittance) filled with
// `background`.
ImageRGB renderWithBackground(const RenderVolume& volume, const Vec3d& position, int width,
                              int height, const float background[3]) {
    EnvmapOptions options;
    options.width = width;
    options.height = height;
    std::copy(background, background + 3, options.background);
    return renderEnvmap(volume, position, options);
}

void meanColour(const ImageRGB& image, float out[3]) {
    double sum[3] = {0, 0, 0};
    for (size_t i = 0; i < image.pixels.size(); ++i) sum[i % 3] += image.pixels[i];
    const double n = double(image.width) * image.height;
    for (int c = 0; c < 3; ++c) out[c] = float(sum[c] / n);
}

// True when every example has the scene.json the oracle is baked from; otherwise says, in one
// line, which one lacks it and that the oracle row is left out.
bool hasSceneFiles(const std::vector<std::string>& dirs, std::ostream& progress) {
    for (const std::string& dir : dirs)
        if (!fs::is_regular_file(fs::path(dir) / dataset::kScene)) {
            progress << "eval: no oracle row: '" << dir
                     << "' has no scene.json (the scene's geometry and "
                     << "light the oracle is baked from); the other rows are computed as usual\n";
            return false;
        }
    return true;
}

}  // namespace

EvalReport evaluate(const EvalOptions& o, std::ostream& progress) {
    if (o.headroom && o.shard.active)
        throw InputError(
            "--headroom cannot be combined with --shard: run the headroom "
            "evaluation in one process");
    std::vector<std::string> dirs = listExamples(o.data);
    if (o.maxScenes > 0 && int(dirs.size()) > o.maxScenes) dirs.resize(size_t(o.maxScenes));
    // A missing render is found before any work or output; a render of the wrong size or with
    // NaN only when its example is read.
    if (o.unclippedPhotos)
        for (const std::string& dir : dirs)
            if (const std::string missing = missingUnclippedView(dir, UnclippedViews::RefAndSrc);
                !missing.empty())
                throw FileError("'" + dir + "' has no " + missing +
                                ": --unclipped-photos needs each example's ref.exr and src.exr");
    PredictorOptions po;
    po.model = o.model;
    po.device = o.device;
    po.threads = o.threads;
    if (o.pruneAlpha >= 0) po.pruneAlpha = o.pruneAlpha;
    po.shell = o.shell;
    po.highlightGain = o.highlightGain;
    po.highlightKnee = o.highlightKnee;
    const Predictor predictor(po);
    const NetConfig& config = predictor.config();
    // Made now, so that an unwritable place fails before the work; taken away again if still
    // empty when evaluate ends, which only a failure leaves it (every eval writes its files at
    // the end), so that a failed eval leaves no empty folder behind.
    struct FolderRemovedIfEmpty {
        fs::path path;
        bool made = false;
        ~FolderRemovedIfEmpty() {
            std::error_code ignored;
            if (made && fs::is_empty(path, ignored)) fs::remove(path, ignored);
        }
    } outFolder{o.out};
    outFolder.made = fs::create_directories(o.out);

    // The oracle re-bakes each scene from its scene.json; a data set made elsewhere (dev_cycles)
    // has none, and a row over only some of its scenes would not compare with the others.
    const bool withOracle = o.oracle && hasSceneFiles(dirs, progress);

    EvalReport report;
    std::vector<std::string> names = {"ours", "ours, MPI only", "single global envmap"};
    if (withOracle) names.push_back("oracle (ceiling)");
    for (const std::string& name : names) {
        report.methods.emplace_back();
        report.methods.back().name = name;
    }
    if (o.headroom)
        for (const TruthPart part : kTruthParts) {
            report.headroom.emplace_back();
            report.headroom.back().name = std::string("ours + ") + truthPartName(part);
        }
    std::vector<std::vector<ImageRGB>> sheetRows;
    std::vector<std::string> sheetRowIds;  // example_envmap, for a shard's strips
    std::vector<std::size_t> sheetRowScenes;
    nlohmann::json shardExamples = nlohmann::json::array();
    std::ostringstream csv;
    csv << evalCsvHeader();
    std::unique_ptr<synth::PanoramaLibrary> panoramas;
    if (withOracle) panoramas = std::make_unique<synth::PanoramaLibrary>(o.hdriDir);

    std::size_t done = 0, owned = 0;
    for (size_t s = 0; s < dirs.size(); ++s) owned += o.shard.owns(s) ? 1 : 0;
    const auto start = std::chrono::steady_clock::now();
    for (size_t s = 0; s < dirs.size(); ++s) {
        if (!o.shard.owns(s)) continue;
        TrainingExample ex = loadExample(dirs[s], /*withMasks=*/true);
        // The global envmap's colour stays the saved photo's mean; the model reads the renders.
        const ImageRGB savedRef = ex.ref;
        if (o.unclippedPhotos && !useUnclippedViews(ex, UnclippedViews::RefAndSrc))
            throw FileError("'" + dirs[s] +
                            "': its ref.exr or src.exr is not of its photos' size, or holds NaN "
                            "(--unclipped-photos)");
        StereoPair pair{ex.ref, ex.src, ex.cameras};
        const Prediction prediction = predictor.predict(pair);
        const RenderVolume ours(prediction.volume), mpiOnly(prediction.mpiOnly);

        float observedMean[3];
        meanColour(savedRef, observedMean);
        const float grey[3] = {kGreyFill, kGreyFill, kGreyFill};
        const auto& firstGt = ex.envmaps.front();
        const ImageRGB global = renderWithBackground(mpiOnly, ex.cameras.ref.position,
                                                     firstGt.width, firstGt.height, observedMean);
        std::unique_ptr<RenderVolume> oracle;
        if (withOracle) {
            synth::BakeOptions bake;
            const synth::Scene scene =
                synth::loadScene((fs::path(dirs[s]) / dataset::kScene).string(), &bake);
            for (const auto& w : scene.windows) panoramas->get(w.panorama);
            const synth::RayTracer tracer(scene);
            const synth::RadianceField field(scene, tracer, *panoramas, bake);
            const VolumeLayout layout =
                VolumeLayout::fromFarDepth(*ex.cameras.far, config.levels, config.resolution);
            oracle = std::make_unique<RenderVolume>(synth::oracleVolume(scene, field, layout));
        }

        for (size_t e = 0; e < ex.envmaps.size(); ++e) {
            const ImageRGB& gt = ex.envmaps[e];
            const Vec3d position = ex.cameras.envmaps[e].position;
            EnvmapOptions options;
            options.width = gt.width;
            options.height = gt.height;
            std::vector<ImageRGB> predictions = {
                renderEnvmap(ours, position, options),
                renderWithBackground(mpiOnly, position, gt.width, gt.height, grey),
                resizeImage(global, gt.width, gt.height)};
            if (oracle) predictions.push_back(renderEnvmap(*oracle, position, options));
            const std::string example = fs::path(dirs[s]).filename().string();
            for (size_t m = 0; m < predictions.size(); ++m) {
                const MetricValues values =
                    metricColumns(compareEnvmaps(predictions[m], gt, &ex.masks[e]));
                addScores(report.methods[m], values);
                csv << evalCsvRow(example, e, report.methods[m].name, values, o.shard.active);
            }
            for (size_t k = 0; k < prediction.emitters.size(); ++k) {
                // A lamp on the envmap's point has no direction to score.
                const Vec3d toLamp = prediction.emitters[k].position - position;
                report.lamps.push_back({example, e, k, prediction.emitters[k].alpha,
                                        toLamp.length() > 1e-9
                                            ? degreesToNearestHighlight(gt, toLamp)
                                            : std::nan("")});
            }
            for (size_t k = 0; k < report.headroom.size(); ++k) {
                const ImageRGB spliced =
                    spliceTruth(predictions[0], gt, kTruthParts[k], ex.masks[e]);
                const MetricValues values =
                    metricColumns(compareEnvmaps(spliced, gt, &ex.masks[e]));
                addScores(report.headroom[k], values);
                csv << evalCsvRow(example, e, report.headroom[k].name, values, false);
            }
            if (sheetRows.size() < kEvalSheetRows) {
                std::vector<ImageRGB> row = {gt};
                row.insert(row.end(), predictions.begin(), predictions.end());
                sheetRows.push_back(std::move(row));
                sheetRowIds.push_back(example + "_" + std::to_string(e));
                sheetRowScenes.push_back(s);
            }
        }
        shardExamples.push_back({{"index", s}, {"id", fs::path(dirs[s]).filename().string()}});
        progress << "eval: " << ++done << "/" << owned << " scenes  (ours " << std::fixed
                 << std::setprecision(2) << meanStd(report.methods[0].psnrAll).mean
                 << " dB so far, predict " << prediction.seconds << " s)" << std::defaultfloat
                 << std::endl;
    }

    report.markdown = evalTableMarkdown(report.methods, owned, o.data, config.name);
    report.markdown += evalPredictionNotes(predictor.highlightGain(), predictor.highlightKnee(),
                                           o.shell, o.unclippedPhotos);
    if (o.headroom) report.markdown += headroomTableMarkdown(report.methods[0], report.headroom);
    if (!o.shard.active) report.markdown += lampPlacementMarkdown(report.lamps);
    if (o.shard.active) {
        // The shard's share: exact metrics, the strips of its first contact-sheet rows and the
        // record that the merge reads.
        const std::string tag = o.shard.tag();
        const fs::path stripDir = fs::path(o.out) / ("sheet." + tag);
        fs::create_directories(stripDir);
        nlohmann::json strips = nlohmann::json::array();
        for (std::size_t r = 0; r < sheetRows.size(); ++r) {
            const std::string file = "sheet." + tag + "/" + sheetRowIds[r] + ".exr";
            writeImage(sheetStrip(sheetRows[r]), (fs::path(o.out) / file).string());
            strips.push_back({{"scene", sheetRowScenes[r]}, {"file", file}});
        }
        std::vector<std::string> methodNames;
        for (const auto& m : report.methods) methodNames.push_back(m.name);
        const nlohmann::json record = {
            {"kind", "eval"},
            {"shard", o.shard.index},
            {"shards", o.shard.count},
            {"eval",
             {{"data", o.data},
              {"model", o.model},
              {"config", config.name},
              {"scenes", dirs.size()},
              {"max_scenes", o.maxScenes},
              {"methods", methodNames},
              {"prune_alpha", predictor.pruneAlpha()},
              {"shell", o.shell},
              {"unclipped_photos", o.unclippedPhotos},
              {"highlight_gain", predictor.highlightGain()},
              {"highlight_knee", predictor.highlightKnee()}}},
            {"csv", "metrics." + tag + ".csv"},
            {"sheet_rows", strips},
            {"examples", shardExamples},
            {"seconds",
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}};
        writeTextFile((fs::path(o.out) / ("metrics." + tag + ".csv")).string(), csv.str());
        writeTextFile((fs::path(o.out) / o.shard.recordName()).string(), record.dump(1));
        progress << "eval: shard " << o.shard.index << " of " << o.shard.count << " -> " << o.out
                 << "/" << o.shard.recordName() << "; `lighthouse merge " << o.out
                 << "` writes table.md once every shard is done\n";
        return report;
    }
    writeTextFile((fs::path(o.out) / "table.md").string(), report.markdown);
    writeTextFile((fs::path(o.out) / "metrics.csv").string(), csv.str());
    if (!report.lamps.empty())
        writeTextFile((fs::path(o.out) / "lamps.csv").string(), lampPlacementCsv(report.lamps));
    writePng(contactSheet(sheetRows, kEvalSheetTileHeight),
             (fs::path(o.out) / "contact_sheet.png").string());
    progress << "eval: columns of contact_sheet.png: ground truth | ours | MPI only | global envmap"
             << (withOracle ? " | oracle" : "") << "\n";
    return report;
}

}  // namespace lh::net
