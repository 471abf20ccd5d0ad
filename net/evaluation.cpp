#include "net/evaluation.h"

#include "core/atomic_file.h"
#include "core/errors.h"
#include "net/predictor.h"
#include "net/training_data.h"
#include "render/contact_sheet.h"
#include "render/envmap.h"
#include "render/image_io.h"
#include "render/metrics.h"
#include "render/render_volume.h"
#include "synth/oracle.h"
#include "synth/panorama.h"
#include "synth/radiance_field.h"
#include "synth/ray_tracer.h"
#include "synth/scene_json.h"

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
ImageRGB renderWithBackground(const RenderVolume& volume, const Vec3d& position, int width, int height,
                              const float background[3]) {
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

std::string cell(const std::vector<double>& values, int precision) {
    const MeanStd m = meanStd(values);
    std::ostringstream out;
    out << std::fixed << std::setprecision(precision) << m.mean << " +- " << m.std;
    return out.str();
}

// True when every example has the scene.json the oracle is baked from; otherwise says, in one
// line, which one lacks it and that the oracle row is left out.
bool hasSceneFiles(const std::vector<std::string>& dirs, std::ostream& progress) {
    for (const std::string& dir : dirs)
        if (!fs::is_regular_file(fs::path(dir) / "scene.json")) {
            progress << "eval: no oracle row: '" << dir << "' has no scene.json (the scene's geometry and "
                     << "light the oracle is baked from); the other rows are computed as usual\n";
            return false;
        }
    return true;
}

}  // namespace

EvalReport evaluate(const EvalOptions& o, std::ostream& progress) {
    std::vector<std::string> dirs = listExamples(o.data);
    if (o.maxScenes > 0 && int(dirs.size()) > o.maxScenes) dirs.resize(size_t(o.maxScenes));
    PredictorOptions po;
    po.model = o.model;
    po.device = o.device;
    po.threads = o.threads;
    if (o.pruneAlpha >= 0) po.pruneAlpha = o.pruneAlpha;
    const Predictor predictor(po);
    const NetConfig& config = predictor.config();
    fs::create_directories(o.out);

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
    std::vector<std::vector<ImageRGB>> sheetRows;
    std::ostringstream csv;
    csv << "example,envmap,method,psnr_all_db,angular_all_deg,psnr_observed_db,angular_observed_deg,"
           "log_lum_rmse_all,log_lum_rmse_observed,irradiance_rel_error\n";
    std::unique_ptr<synth::PanoramaLibrary> panoramas;
    if (withOracle) panoramas = std::make_unique<synth::PanoramaLibrary>(o.hdriDir);

    for (size_t s = 0; s < dirs.size(); ++s) {
        const TrainingExample ex = loadExample(dirs[s], /*withMasks=*/true);
        StereoPair pair{ex.ref, ex.src, ex.cameras};
        const Prediction prediction = predictor.predict(pair);
        const RenderVolume ours(prediction.volume), mpiOnly(prediction.mpiOnly);

        float observedMean[3];
        meanColour(ex.ref, observedMean);
        const float grey[3] = {kGreyFill, kGreyFill, kGreyFill};
        const auto& firstGt = ex.envmaps.front();
        const ImageRGB global = renderWithBackground(mpiOnly, ex.cameras.ref.position, firstGt.width,
                                                     firstGt.height, observedMean);
        std::unique_ptr<RenderVolume> oracle;
        if (withOracle) {
            synth::BakeOptions bake;
            const synth::Scene scene = synth::loadScene((fs::path(dirs[s]) / "scene.json").string(), &bake);
            for (const auto& w : scene.windows) panoramas->get(w.panorama);
            const synth::RayTracer tracer(scene);
            const synth::RadianceField field(scene, tracer, *panoramas, bake);
            const VolumeLayout layout = VolumeLayout::fromFarDepth(*ex.cameras.far, config.levels, config.resolution);
            oracle = std::make_unique<RenderVolume>(synth::oracleVolume(scene, field, layout));
        }

        for (size_t e = 0; e < ex.envmaps.size(); ++e) {
            const ImageRGB& gt = ex.envmaps[e];
            const Vec3d position = ex.cameras.envmaps[e].position;
            EnvmapOptions options;
            options.width = gt.width;
            options.height = gt.height;
            std::vector<ImageRGB> predictions = {renderEnvmap(ours, position, options),
                                                 renderWithBackground(mpiOnly, position, gt.width, gt.height, grey),
                                                 resizeImage(global, gt.width, gt.height)};
            if (oracle) predictions.push_back(renderEnvmap(*oracle, position, options));
            for (size_t m = 0; m < predictions.size(); ++m) {
                const EnvmapMetrics metrics = compareEnvmaps(predictions[m], gt, &ex.masks[e]);
                auto& scores = report.methods[m];
                scores.psnrAll.push_back(metrics.psnrAll);
                scores.angularAll.push_back(metrics.angularAll);
                scores.psnrObserved.push_back(metrics.psnrObserved);
                scores.angularObserved.push_back(metrics.angularObserved);
                scores.logLuminanceAll.push_back(metrics.logLuminanceAll);
                scores.logLuminanceObserved.push_back(metrics.logLuminanceObserved);
                scores.irradianceError.push_back(metrics.irradianceError);
                csv << fs::path(dirs[s]).filename().string() << ',' << e << ",\"" << scores.name << "\","
                    << metrics.psnrAll << ',' << metrics.angularAll << ',' << metrics.psnrObserved << ','
                    << metrics.angularObserved << ',' << metrics.logLuminanceAll << ','
                    << metrics.logLuminanceObserved << ',' << metrics.irradianceError << '\n';
            }
            if (sheetRows.size() < 12) {
                std::vector<ImageRGB> row = {gt};
                row.insert(row.end(), predictions.begin(), predictions.end());
                sheetRows.push_back(std::move(row));
            }
        }
        progress << "eval: " << s + 1 << "/" << dirs.size() << " scenes  (ours " << std::fixed << std::setprecision(2)
                 << meanStd(report.methods[0].psnrAll).mean << " dB so far, predict " << prediction.seconds << " s)"
                 << std::defaultfloat << std::endl;
    }

    std::ostringstream md;
    md << "| method | PSNR all (dB) | angular all (deg) | PSNR observed (dB) | angular observed (deg) "
          "| log-lum RMSE all | log-lum RMSE observed | irradiance rel. error |\n"
       << "|---|---|---|---|---|---|---|---|\n";
    for (const auto& m : report.methods)
        md << "| " << m.name << " | " << cell(m.psnrAll, 2) << " | " << cell(m.angularAll, 2) << " | "
           << cell(m.psnrObserved, 2) << " | " << cell(m.angularObserved, 2) << " | "
           << cell(m.logLuminanceAll, 3) << " | " << cell(m.logLuminanceObserved, 3) << " | "
           << cell(m.irradianceError, 3) << " |\n";
    md << "\n" << report.methods[0].psnrAll.size() << " envmaps (" << dirs.size()
       << " scenes) of `" << o.data << "`, model config `" << config.name << "`; mean +- std. "
       << "Log-lum RMSE: of ln(1 + luminance); irradiance rel. error: |E_pred - E_gt| / E_gt at "
       << "the six axis normals (docs/metrics.md).\n";
    report.markdown = md.str();
    writeTextFile((fs::path(o.out) / "table.md").string(), report.markdown);
    writeTextFile((fs::path(o.out) / "metrics.csv").string(), csv.str());
    writePng(contactSheet(sheetRows, 90), (fs::path(o.out) / "contact_sheet.png").string());
    progress << "eval: columns of contact_sheet.png: ground truth | ours | MPI only | global envmap"
             << (withOracle ? " | oracle" : "") << "\n";
    return report;
}

}  // namespace lh::net
