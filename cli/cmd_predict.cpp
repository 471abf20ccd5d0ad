// `lighthouse predict --ref REF.png --src SRC.png --cameras cameras.json [--model M] -o scene.vdb`
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/net_commands.h"
#include "core/atomic_file.h"
#include "core/errors.h"
#include "net/predictor.h"
#include "render/envmap.h"
#include "render/image_io.h"
#include "vdb/volume_io.h"

#include <chrono>
#include <iostream>

namespace lh::cli {

namespace {

struct PredictOptions {
    std::string ref, src, cameras, model, output, device = "cpu";
    std::vector<std::string> envmapsAt;
    std::string envmapSize = "240x120";
    float pruneAlpha = net::kDefaultPruneAlpha;
};

void runPredict(const PredictOptions& o, int threads) {
    if (fileExtension(o.output) != ".vdb") throw InputError("output '" + o.output + "' must end in .vdb");
    const auto start = std::chrono::steady_clock::now();
    net::StereoPair pair{readImage(o.ref), readImage(o.src), loadCamerasFile(o.cameras)};
    std::vector<Vec3d> points;
    for (const auto& text : o.envmapsAt) points.push_back(parsePoint(text, "--envmap-at"));
    EnvmapOptions envOptions;
    parseSize(o.envmapSize, envOptions.width, envOptions.height);
    envOptions.validate();
    net::validateStereoPair(pair);

    net::PredictorOptions po;
    po.model = o.model;
    po.device = o.device;
    po.threads = threads;
    po.pruneAlpha = o.pruneAlpha;
    const net::Predictor predictor(po);
    const net::NetConfig& config = predictor.config();
    std::cerr << "predict: model '" << (o.model.empty() ? net::defaultModelPath() : o.model) << "' (config "
              << config.name << ": " << config.width << "x" << config.height << " input, " << config.planes
              << " planes, " << config.levels << " x " << config.resolution << "^3)\n";
    const net::Prediction p = predictor.predict(pair);
    if (p.rangeEstimated) {
        if (p.range.fallback)
            std::cerr << "predict: warning: the pair shows too little texture to estimate depth; using the default range "
                      << p.range.near << " .. " << p.range.far << " (give near/far in cameras.json)\n";
        else
            std::cerr << "predict: depth range estimated from the pair: " << p.range.near << " .. " << p.range.far
                      << " (" << p.range.votes << " pixels voted)\n";
    } else {
        std::cerr << "predict: depth range from cameras.json: " << p.range.near << " .. " << p.range.far << "\n";
    }
    saveVdb(o.output, &p.volume, &p.mpi);
    std::cerr << "predict: network " << p.seconds << " s; " << p.volume.activeVoxelCount() << " active voxels, MPI of "
              << p.mpi.planeCount() << " planes -> " << o.output << "\n";
    if (!points.empty()) {
        const RenderVolume prepared(p.volume);
        for (size_t i = 0; i < points.size(); ++i) {
            const std::string path = numberedPath(withExtension(o.output, ".png"), int(i));
            const std::string exr = withExtension(path, ".exr");
            const ImageRGB env = renderEnvmap(prepared, points[i], envOptions);
            writeImage(env, exr);
            writePng(env, withExtension(exr, ".png"));
            std::cerr << "predict: envmap at (" << points[i].x() << ", " << points[i].y() << ", " << points[i].z()
                      << ") -> " << exr << " (+ .png)\n";
        }
    }
    std::cerr << "predict: done in " << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
              << " s\n";
}

}  // namespace

void addPredictCommand(CLI::App& app, const int& threads) {
    auto o = std::make_shared<PredictOptions>();
    CLI::App* cmd = app.add_subcommand("predict", netCommandDescription("predict"));
    cmd->add_option("--ref", o->ref, "Reference image (.png/.jpg sRGB or .exr linear)")->required();
    cmd->add_option("--src", o->src, "Second image of the stereo pair")->required();
    cmd->add_option("--cameras", o->cameras, "cameras.json with ref and src (near/far optional: estimated if absent)")
        ->required();
    cmd->add_option("--model", o->model, "Model file (default: the bundled model)");
    cmd->add_option("--prune-alpha", o->pruneAlpha,
                    "Leave voxels whose opacity is below this empty (sparsity; 0 keeps nearly all)")
        ->capture_default_str();
    cmd->add_option("--device", o->device, "cpu, or cuda with a CUDA build of libtorch (not yet tested on a GPU)")
        ->capture_default_str();
    cmd->add_option("--envmap-at", o->envmapsAt, "Also render envmaps at these points X,Y,Z (next to the output)");
    cmd->add_option("--envmap-size", o->envmapSize, "Size of those envmaps, WxH")->capture_default_str();
    cmd->add_option("-o,--output", o->output, "Output .vdb (MPI planes + lighting volume levels)")->required();
    cmd->callback([o, &threads] { runPredict(*o, threads); });
}

}  // namespace lh::cli
