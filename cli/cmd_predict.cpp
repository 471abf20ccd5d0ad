// `lighthouse predict --ref REF.png --src SRC.png --cameras cameras.json [--model M] [--at X,Y,Z
// ...]
//  [--points FILE] [--png] -o scene.vdb`
// `lighthouse predict --pairs LIST | --examples DIR -o OUT_DIR [--shard K/N]`: many pairs, one
// model load; OUT_DIR/NAME.vdb each, and predictions.json (or a shard record, cli/shard_merge.h).
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "cli/net_commands.h"
#include "cli/shard_merge.h"
#include "core/atomic_file.h"
#include "core/dataset_files.h"
#include "core/errors.h"
#include "core/shard.h"
#include "image/image_io.h"
#include "net/predictor.h"
#include "net/training_data.h"
#include "render/envmap.h"
#include "vdb/mantissa_rounding.h"
#include "vdb/volume_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

namespace lh::cli {

namespace {

struct PredictOptions {
    std::string ref, src, cameras, model, output, device = "cpu";
    std::vector<std::string> envmapsAt;  // --at
    std::string pointsFile;              // --points
    std::string envmapSize = "240x120";
    bool alsoPng = false;
    float exposure = 1.f;
    bool half = false;
    int mantissaBits = 0;          // 0: values as the network gives them
    float pruneAlpha = -1;         // the model's (net/predictor.h)
    bool shell = kShellByDefault;  // collapse the unseen medium into a shell (net/predictor.h)
    double highlightGain = -1;     // the model's (net/predictor.h)
    double highlightKnee = 1;      // where the gain starts (net/predictor.h)
    std::string pairs, examples, shard;  // batch form
};

namespace fs = std::filesystem;

// One pair of the batch form: its name (of the output, NAME.vdb) and files.
struct BatchItem {
    std::string name, ref, src, cameras;
};

// The list file: one pair a line, "REF SRC CAMERAS [NAME]", paths relative to the list's
// folder; blank lines and lines starting with '#' are skipped. NAME defaults to the pair's
// 0-based number, 000000, 000001, ...
std::vector<BatchItem> readPairList(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw FileError("cannot read the list of pairs '" + path + "'");
    const fs::path base = fs::path(path).parent_path();
    const auto resolve = [&](const std::string& p) {
        return fs::path(p).is_absolute() ? p : (base / p).string();
    };
    std::vector<BatchItem> items;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::istringstream fields(line);
        std::vector<std::string> f;
        for (std::string w; fields >> w;) f.push_back(w);
        if (f.empty() || f[0][0] == '#') continue;
        if (f.size() < 3 || f.size() > 4)
            throw InputError("'" + path + "' line " + std::to_string(number) +
                             ": expected REF SRC CAMERAS [NAME], got '" + line + "'");
        char id[16];
        std::snprintf(id, sizeof id, "%06zu", items.size());
        items.push_back(
            {f.size() == 4 ? f[3] : std::string(id), resolve(f[0]), resolve(f[1]), resolve(f[2])});
    }
    if (items.empty())
        throw InputError("'" + path + "' lists no pairs (lines REF SRC CAMERAS [NAME])");
    return items;
}

std::vector<BatchItem> batchItems(const PredictOptions& o) {
    std::vector<BatchItem> items;
    if (!o.pairs.empty()) {
        items = readPairList(o.pairs);
    } else {
        for (const std::string& dir : net::listExamples(o.examples)) {
            const fs::path d(dir);
            items.push_back({d.filename().string(), (d / dataset::viewPng("ref")).string(),
                             (d / dataset::viewPng("src")).string(),
                             (d / dataset::kCameras).string()});
        }
    }
    std::set<std::string> names;
    for (const BatchItem& item : items) {
        if (item.name.empty() || item.name.find('/') != std::string::npos || item.name[0] == '.')
            throw InputError("pair name '" + item.name + "' is not a plain file name");
        if (!names.insert(item.name).second)
            throw InputError("two pairs are named '" + item.name + "'");
    }
    return items;
}

net::PredictorOptions predictorOptions(const PredictOptions& o, int threads) {
    net::PredictorOptions po;
    po.model = o.model;
    po.device = o.device;
    po.threads = threads;
    po.pruneAlpha = o.pruneAlpha;
    po.shell = o.shell;
    po.highlightGain = o.highlightGain;
    po.highlightKnee = o.highlightKnee;
    return po;
}

// Whether the network reads what the reference photo holds above 1 (only an EXR photo holds
// any): a user who gives one to a model that clips it, or a PNG to a model whose lamp head
// would read it, should hear which.
void notePhotoRadianceAboveOne(const ImageRGB& ref, const net::NetConfig& config) {
    std::size_t above = 0;
    for (const float value : ref.pixels) above += value > 1.f ? 1 : 0;
    // Of the photo's channel values, to two decimals.
    const double percent =
        std::round(1e4 * double(above) / double(std::max<std::size_t>(1, ref.pixels.size()))) /
        100.0;
    if (above > 0 && !config.emitterPhotoUnclipped)
        std::cerr << "predict: the reference photo's values above 1 (" << percent
                  << "% of them) are read clipped at 1, as the model was trained\n";
    else if (above > 0)
        std::cerr << "predict: the lamp head reads the reference photo's values above 1 ("
                  << percent << "% of them); the rest of the network reads them clipped at 1\n";
    else if (config.emitterPhotoUnclipped)
        std::cerr << "predict: note: this model's lamp head reads a photo's values above 1, and "
                     "this one has none (give a linear EXR photo for it)\n";
}

// A knee only says where a gain starts: without a gain it changes nothing, which a user who
// asked for one should hear.
void warnOfKneeWithoutGain(const net::Predictor& predictor) {
    if (predictor.highlightKnee() != 1.0 && predictor.highlightGain() == 1.0)
        std::cerr << "predict: warning: --highlight-knee changes nothing without a gain "
                     "(--highlight-gain, or a model trained under one)\n";
}

void runPredictBatch(const PredictOptions& o, int threads) {
    if (!o.pairs.empty() && !o.examples.empty())
        throw InputError("give --pairs or --examples, not both");
    if (!o.ref.empty() || !o.src.empty() || !o.cameras.empty())
        throw InputError(
            "--ref, --src and --cameras are for one pair; --pairs and --examples list many");
    if (!o.envmapsAt.empty() || !o.pointsFile.empty() || o.alsoPng)
        throw InputError(
            "--at, --points and --png are for one pair, not with --pairs or --examples");
    if (fileExtension(o.output) == ".vdb")
        throw InputError("with --pairs or --examples, -o is a directory (NAME.vdb each), not '" +
                         o.output + "'");
    const Shard shard = o.shard.empty() ? Shard{} : parseShard(o.shard);
    const std::vector<BatchItem> items = batchItems(o);
    fs::create_directories(o.output);
    const net::Predictor predictor(predictorOptions(o, threads));
    warnOfKneeWithoutGain(predictor);
    std::size_t owned = 0, done = 0;
    for (std::size_t i = 0; i < items.size(); ++i) owned += shard.owns(i) ? 1 : 0;
    std::cerr << "predict: " << owned << " of " << items.size() << " pairs";
    if (shard.active) std::cerr << " (shard " << shard.index << " of " << shard.count << ")";
    std::cerr << " -> " << o.output << "/NAME.vdb\n";
    const auto start = std::chrono::steady_clock::now();
    nlohmann::json entries = nlohmann::json::array();
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (!shard.owns(i)) continue;
        const BatchItem& item = items[i];
        net::StereoPair pair{readImage(item.ref), readImage(item.src),
                             loadCamerasFile(item.cameras)};
        net::validateStereoPair(pair);
        for (const auto& w : net::stereoPairWarnings(pair)) std::cerr << "warning: " << w << "\n";
        const net::Prediction p = predictor.predict(pair);
        const std::string output = item.name + ".vdb";
        warnOfHalfClamping(saveVdb((fs::path(o.output) / output).string(), &p.volume, &p.mpi,
                                   VolumeSaveOptions{o.half, o.mantissaBits}),
                           "--half");
        nlohmann::json entry = predictionEntry(item.name, item.ref, item.src, item.cameras, output);
        entry["index"] = i;
        entry["seconds"] = p.seconds;
        entries.push_back(entry);
        std::cerr << "predict: " << ++done << "/" << owned << " " << item.name << ": network "
                  << p.seconds << " s, " << p.volume.activeVoxelCount() << " active voxels\n";
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string model = o.model.empty() ? net::defaultModelPath() : o.model;
    if (shard.active) {
        const nlohmann::json record = {
            {"kind", "predict"},     {"shard", shard.index},
            {"shards", shard.count}, {"predict", {{"model", model}, {"pairs", items.size()}}},
            {"seconds", seconds},    {"items", entries}};
        writeTextFile((fs::path(o.output) / shard.recordName()).string(), record.dump(1));
        std::cerr << "predict: shard done in " << seconds << " s -> " << o.output << "/"
                  << shard.recordName() << "; `lighthouse merge " << o.output
                  << "` writes predictions.json once every shard is done\n";
        return;
    }
    for (auto& e : entries) {
        e.erase("index");
        e.erase("seconds");
    }
    writeTextFile((fs::path(o.output) / kPredictionsIndex).string(),
                  predictionsIndex(model, entries).dump(1));
    std::cerr << "predict: " << items.size() << " pairs in " << seconds << " s -> " << o.output
              << "/" << kPredictionsIndex << "\n";
}

void runPredict(const PredictOptions& o, int threads) {
    validateMantissaBits(o.mantissaBits, o.half);
    if (!o.pairs.empty() || !o.examples.empty()) return runPredictBatch(o, threads);
    if (!o.shard.empty())
        throw InputError("--shard needs the batch form, --pairs LIST or --examples DIR");
    if (o.ref.empty() || o.src.empty() || o.cameras.empty())
        throw InputError(
            "predict needs --ref, --src and --cameras (one pair), or --pairs LIST or --examples "
            "DIR");
    requireVdbOutput(o.output, "the MPI and the lighting volume");
    requireWritableOutput(o.output);  // before the network's seconds, not after them
    const auto start = std::chrono::steady_clock::now();
    net::StereoPair pair{readImage(o.ref), readImage(o.src), loadCamerasFile(o.cameras)};
    std::vector<Vec3d> points;
    for (const auto& text : o.envmapsAt) points.push_back(parsePoint(text, "--at"));
    if (!o.pointsFile.empty())
        for (const Vec3d& p : readPointsFile(o.pointsFile)) points.push_back(p);
    requirePositiveExposure(o.exposure);
    if (points.empty() && (o.alsoPng || o.exposure != 1.f))
        throw InputError(
            "--png and --exposure are for the envmaps of --at or --points, and none was given");
    EnvmapOptions envOptions;
    parseSize(o.envmapSize, envOptions.width, envOptions.height);
    envOptions.validate();
    net::validateStereoPair(pair);
    for (const auto& w : net::stereoPairWarnings(pair)) std::cerr << "warning: " << w << "\n";

    const net::Predictor predictor(predictorOptions(o, threads));
    warnOfKneeWithoutGain(predictor);
    const net::NetConfig& config = predictor.config();
    std::cerr << "predict: model '" << (o.model.empty() ? net::defaultModelPath() : o.model)
              << "' (config " << config.name << ": " << config.width << "x" << config.height
              << " input, " << config.planes << " planes, " << config.levels << " x "
              << config.resolution << "^3)\n";
    notePhotoRadianceAboveOne(pair.ref, config);
    const net::Prediction p = predictor.predict(pair);
    if (p.rangeEstimated) {
        if (p.range.fallback)
            std::cerr << "predict: warning: the pair shows too little texture to estimate depth; "
                         "using the default range "
                      << p.range.near << " .. " << p.range.far
                      << " (give near/far in cameras.json)\n";
        else
            std::cerr << "predict: depth range estimated from the pair: " << p.range.near << " .. "
                      << p.range.far << " (" << p.range.votes << " pixels voted)\n";
    } else {
        std::cerr << "predict: depth range from cameras.json: " << p.range.near << " .. "
                  << p.range.far << "\n";
    }
    warnOfHalfClamping(
        saveVdb(o.output, &p.volume, &p.mpi, VolumeSaveOptions{o.half, o.mantissaBits}), "--half");
    std::ostringstream gainNote;  // the highlight gain, where one is applied
    if (predictor.highlightGain() != 1.0 && predictor.highlightKnee() == 1.0)
        gainNote << ", above white x" << predictor.highlightGain();
    else if (predictor.highlightGain() != 1.0)
        gainNote << ", above luminance " << predictor.highlightKnee() << " x"
                 << predictor.highlightGain();
    std::cerr << "predict: network " << p.seconds << " s; " << p.volume.activeVoxelCount()
              << " active voxels (alpha >= " << predictor.pruneAlpha() << gainNote.str()
              << (o.shell ? ", collapsed into a shell" : "") << "), MPI of " << p.mpi.planeCount()
              << " planes -> " << o.output << "\n";
    for (size_t k = 0; k < p.emitters.size(); ++k) {
        const net::PredictedEmitter& e = p.emitters[k];
        std::cerr << "predict: emitter " << k + 1 << " at (" << e.position.x() << ", "
                  << e.position.y() << ", " << e.position.z() << ") m, radius " << e.radius
                  << " m, opacity " << e.alpha << ", radiance (" << e.radiance.x() << ", "
                  << e.radiance.y() << ", " << e.radiance.z() << ")\n";
    }
    if (!points.empty()) {
        warnOfPointsOutside(p.volume, points);
        const RenderVolume prepared(p.volume);
        for (size_t i = 0; i < points.size(); ++i) {
            const std::string path = numberedPath(withExtension(o.output, ".png"), int(i));
            const std::string exr = withExtension(path, ".exr");
            const ImageRGB env = renderEnvmap(prepared, points[i], envOptions);
            writeImage(env, exr);
            if (o.alsoPng) writePng(env, withExtension(exr, ".png"), o.exposure);
            std::cerr << "predict: envmap at (" << points[i].x() << ", " << points[i].y() << ", "
                      << points[i].z() << ") -> " << exr << (o.alsoPng ? " (+ .png)" : "") << "\n";
        }
    }
    std::cerr << "predict: done in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
              << " s\n";
}

}  // namespace

void addPredictCommand(CLI::App& app, const int& threads) {
    auto o = std::make_shared<PredictOptions>();
    CLI::App* cmd = app.add_subcommand("predict", netCommandDescription("predict"));
    cmd->add_option("--ref", o->ref,
                    "Reference image (.png/.jpg sRGB or .exr linear; the network reads an EXR "
                    "clipped at 1, as a camera saves it, and only a '+unclipped' model's lamp "
                    "head also reads the radiance above 1)");
    cmd->add_option("--src", o->src, "Second image of the stereo pair");
    cmd->add_option("--cameras", o->cameras,
                    "cameras.json with ref and src (near/far optional: estimated if absent)");
    cmd->add_option("--pairs", o->pairs,
                    "Batch: a list file, one pair a line 'REF SRC CAMERAS [NAME]' (paths relative "
                    "to the list); "
                    "-o is then a directory of NAME.vdb and predictions.json");
    cmd->add_option("--examples", o->examples,
                    "Batch: every example of a data set (ref.png, src.png, cameras.json), NAME = "
                    "its directory");
    cmd->add_option(
        "--shard", o->shard,
        "Batch: K/N, predict only pair i with i mod N = K (0-based) and write a shard record; "
        "`lighthouse merge OUT` writes predictions.json of all shards");
    cmd->add_option("--model", o->model, "Model file (default: the bundled model)");
    cmd->add_flag("--shell,!--no-shell", o->shell,
                  "Collapse the predicted medium the reference camera did not see into an opaque "
                  "shell as seen from the middle of the room, keeping what it saw as predicted: "
                  "envmaps render about three times faster, as accurate on average (the default; "
                  "--no-shell writes the predicted fog as it is, e.g. to study or edit it; "
                  "docs/network.md, \"The shell\")");
    cmd->add_option("--highlight-gain", o->highlightGain,
                    "Multiply what each voxel holds above white by this, hue kept: the lamps and "
                    "windows the model shows only a little brighter than white get back the light "
                    "they give; nothing at or below white changes (1-1000; docs/network.md). "
                    "Default: the gain the model was trained under, else 1")
        ->check(CLI::Range(1.0, net::kMaxHighlightGain));
    cmd->add_option("--highlight-knee", o->highlightKnee,
                    "Expand only what lies above this luminance: a voxel of luminance Y above it "
                    "becomes KNEE + GAIN (Y - KNEE), so that the voxels a little above white "
                    "around a lamp do not draw it too wide (1-100; docs/network.md, \"Brighter "
                    "lamps and windows\")")
        ->check(CLI::Range(1.0, net::kMaxHighlightKnee))
        ->capture_default_str();
    cmd->add_option("--prune-alpha", o->pruneAlpha,
                    "Leave voxels whose opacity is below this empty (sparsity; 0 keeps nearly "
                    "all). Default: the threshold the model was trained under, else 0.03")
        ->check(CLI::Range(0.0f, 1.0f));
    cmd->add_option("--device", o->device,
                    "cpu, or cuda with a CUDA build of libtorch (not yet tested on a GPU)")
        ->capture_default_str();
    cmd->add_option("--at", o->envmapsAt,
                    "Also render an envmap at this point X,Y,Z (repeatable: --at A --at B), "
                    "OUT_000.exr, OUT_001.exr, ... next to the output")
        ->allow_extra_args(false);
    cmd->add_option("--points", o->pointsFile, "Points file of envmaps to render, as --at");
    cmd->add_option("--envmap-size", o->envmapSize, "Size of those envmaps, WxH")
        ->capture_default_str();
    addImageFlags(cmd, o->alsoPng, o->exposure);  // for those envmaps: checked in runPredict
    addHalfFlag(cmd, o->half);
    addMantissaBitsOption(cmd, o->mantissaBits,
                          "Round every value of the volume and the MPI to N mantissa bits (1-22; "
                          "1-9 with --half) for a smaller file: relative error at most "
                          "2^-(N+1), 7 = 0.4%; 0 keeps the values");
    cmd->add_option(
           "-o,--output", o->output,
           "Output .vdb (MPI planes + lighting volume levels); a directory in the batch form")
        ->required();
    cmd->callback([o, &threads] { runPredict(*o, threads); });
}

}  // namespace lh::cli
