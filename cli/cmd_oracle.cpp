// `lighthouse oracle SCENE_DIR -o oracle.vdb [--levels 5 --res 64] [--envmaps-out DIR [--png]]
// [--half]`
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "core/atomic_file.h"
#include "core/dataset_files.h"
#include "core/errors.h"
#include "core/path_guard.h"
#include "image/image_io.h"
#include "render/envmap.h"
#include "synth/oracle.h"
#include "synth/scene_json.h"
#include "vdb/volume_io.h"

#include <filesystem>
#include <iostream>

namespace lh::cli {

namespace {

namespace fs = std::filesystem;

struct OracleCommandOptions {
    std::string sceneDir;
    std::string output;
    int levels = 5;
    int resolution = 64;
    int supersample = 3;
    std::string envmapsOut;
    std::string hdriDir = LIGHTHOUSE_HDRI_DIR;
    bool half = false;
    bool alsoPng = false;
    float exposure = 1.f;
};

void runOracle(const OracleCommandOptions& o) {
    const fs::path dir(o.sceneDir);
    if (!fs::is_directory(dir))
        throw FileError("'" + o.sceneDir +
                        "' is not an example directory (expected scene.json and cameras.json)");
    // The oracle may go inside the example (synth puts oracle.vdb there), but not onto what it
    // reads.
    const std::vector<NamedInput> inputs = {
        {(dir / dataset::kScene).string(), "the example's scene.json"},
        {(dir / dataset::kCameras).string(), "the example's cameras.json"},
        {o.hdriDir, "--hdri-dir"}};
    requireVdbOutput(o.output, "the oracle lighting volume");
    requireOutputIsNotAnInput(o.output, "-o", inputs);
    requirePositiveExposure(o.exposure);
    synth::BakeOptions bake;
    const synth::Scene scene = synth::loadScene((dir / dataset::kScene).string(), &bake);
    const CamerasFile cameras = loadCamerasFile((dir / dataset::kCameras).string());
    if (!o.envmapsOut.empty())
        for (const auto& e : cameras.envmaps) {  // the ground-truth envmaps are read for their size
            const std::vector<NamedInput> truth = {
                {(dir / e.file).string(), "the example's " + e.file}};
            const std::string out = (fs::path(o.envmapsOut) / e.file).string();
            requireOutputIsNotAnInput(out, "--envmaps-out", truth);
            if (o.alsoPng) requireOutputIsNotAnInput(withExtension(out, ".png"), "--png", truth);
        }
    if (!cameras.far)
        throw InputError("'" + (dir / dataset::kCameras).string() + "' has no 'far' depth");
    const VolumeLayout layout = VolumeLayout::fromFarDepth(*cameras.far, o.levels, o.resolution);

    std::cerr << "oracle: baking the scene's light (" << scene.primitives.size()
              << " primitives)\n";
    synth::PanoramaLibrary panoramas(o.hdriDir);
    for (const auto& w : scene.windows) panoramas.get(w.panorama);
    const synth::RayTracer tracer(scene);
    const synth::RadianceField field(scene, tracer, panoramas, bake);
    std::cerr << "oracle: voxelising into " << layout.levels << " x " << layout.resolution
              << "^3\n";
    LightingVolume volume = synth::oracleVolume(scene, field, layout, {o.supersample, 8.0});
    volume.refCamera = cameras.ref;
    warnOfHalfClamping(saveVolume(o.output, volume, VolumeSaveOptions{o.half}), "--half");
    std::cerr << "oracle: " << volume.activeVoxelCount() << " active voxels -> " << o.output
              << "\n";

    if (!o.envmapsOut.empty()) {
        fs::create_directories(o.envmapsOut);
        const RenderVolume prepared(volume);
        for (const auto& e : cameras.envmaps) {
            const ImageRGB probe = readImage((dir / e.file).string());  // size of the ground truth
            EnvmapOptions options;
            options.width = probe.width;
            options.height = probe.height;
            const std::string out = (fs::path(o.envmapsOut) / e.file).string();
            const ImageRGB envmap = renderEnvmap(prepared, e.position, options);
            writeImage(envmap, out, o.exposure);
            const bool png = o.alsoPng && fileExtension(out) == ".exr";
            if (png) writePng(envmap, withExtension(out, ".png"), o.exposure);
            std::cerr << "oracle: envmap at (" << e.position.x() << ", " << e.position.y() << ", "
                      << e.position.z() << ") -> " << out << (png ? " (+ .png)" : "") << "\n";
        }
    }
}

}  // namespace

void addOracleCommand(CLI::App& app) {
    auto o = std::make_shared<OracleCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "oracle",
        "Voxelise a synthetic example's true geometry and radiance into a lighting volume");
    cmd->add_option("scene", o->sceneDir, "Example directory written by `lighthouse synth`")
        ->required();
    cmd->add_option("-o,--output", o->output, "Output .vdb")->required();
    cmd->add_option("--levels", o->levels, "Nested levels")->capture_default_str();
    cmd->add_option("--res", o->resolution, "Voxels per side of every level")
        ->capture_default_str();
    cmd->add_option("--supersample", o->supersample, "Sub-samples per voxel and axis")
        ->capture_default_str();
    CLI::Option* envmaps = cmd->add_option("--envmaps-out", o->envmapsOut,
                                           "Also render the oracle's envmaps at the example's "
                                           "ground-truth points into this directory");
    addImageFlags(cmd, o->alsoPng, o->exposure).need(envmaps);
    addHalfFlag(cmd, o->half);
    cmd->add_option("--hdri-dir", o->hdriDir, "Folder of the panoramas the scene's windows use")
        ->capture_default_str();
    cmd->callback([o] { runOracle(*o); });
}

}  // namespace lh::cli
