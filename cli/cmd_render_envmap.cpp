// `lighthouse render-envmap FILE.vdb --at X,Y,Z [...] -o OUT.exr|.png`
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "cli/quadrature_flags.h"
#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/path_guard.h"
#include "image/image_io.h"
#include "render/envmap.h"

#include <chrono>
#include <iostream>

namespace lh::cli {

namespace {

struct RenderEnvmapOptions {
    std::string file;
    std::vector<std::string> at;
    std::string pointsFile;
    std::string size = "240x120";
    float exposure = 1.f;
    QuadratureFlags quadrature;
    double threshold = MarchOptions{}.minTransmittance;
    bool reference = false;
    bool alsoPng = false;
    bool strict = false;
    std::string output;
};

void renderEnvmaps(const RenderEnvmapOptions& o) {
    const std::string ext = fileExtension(o.output);
    if (ext != ".exr" && ext != ".png")
        throw InputError("output '" + o.output + "' must end in .exr or .png");
    requirePositiveExposure(o.exposure);
    EnvmapOptions options;
    parseSize(o.size, options.width, options.height);
    if (o.reference) {
        options.march = MarchOptions::reference();
    } else {
        o.quadrature.applyTo(options.march);
        options.march.minTransmittance = o.threshold;
    }
    options.validate();

    std::vector<Vec3d> points;
    for (const auto& text : o.at) points.push_back(parsePoint(text, "--at"));
    if (!o.pointsFile.empty())
        for (const auto& p : readPointsFile(o.pointsFile)) points.push_back(p);
    if (points.empty())
        throw InputError("give at least one point with --at X,Y,Z or --points FILE");
    const auto outputPath = [&](std::size_t i) {
        return points.size() == 1 ? o.output : numberedPath(o.output, int(i));
    };
    const std::vector<NamedInput> inputs = {{o.file, "the input volume"},
                                            {o.pointsFile, "--points"}};
    for (std::size_t i = 0; i < points.size(); ++i) {
        requireOutputIsNotAnInput(outputPath(i), "-o", inputs);
        if (o.alsoPng && ext == ".exr")
            requireOutputIsNotAnInput(withExtension(outputPath(i), ".png"), "--png", inputs);
    }

    const LightingVolume volume = loadVolumeForCli(o.file, o.strict);
    const RenderVolume prepared(volume);
    warnOfPointsOutside(volume, points);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const auto start = std::chrono::steady_clock::now();
        const ImageRGB envmap = renderEnvmap(prepared, points[i], options);
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        const std::string path = outputPath(i);
        writeImage(envmap, path, o.exposure);
        if (o.alsoPng && ext == ".exr") writePng(envmap, withExtension(path, ".png"), o.exposure);
        std::cerr << "[" << i + 1 << "/" << points.size() << "] envmap at (" << points[i].x()
                  << ", " << points[i].y() << ", " << points[i].z() << ") " << options.width << "x"
                  << options.height << " in " << ms << " ms -> " << path << "\n";
    }
}

}  // namespace

void addRenderEnvmapCommand(CLI::App& app) {
    auto o = std::make_shared<RenderEnvmapOptions>();
    CLI::App* cmd = app.add_subcommand(
        "render-envmap", "Render equirectangular envmaps (incident radiance) at world points");
    cmd->add_option("file", o->file, "Lighting volume (.vdb)")->required();
    cmd->add_option("--at", o->at, "World point X,Y,Z (repeatable: --at A --at B)")
        ->allow_extra_args(false);
    cmd->add_option("--points", o->pointsFile, "Points file: one point 'x y z' per line");
    cmd->add_option("--size", o->size, "Envmap size WxH with W = 2H")->capture_default_str();
    addQuadratureFlags(cmd, o->quadrature);
    cmd->add_option(
           "--threshold", o->threshold,
           "Stop a ray once its transmittance drops below this; what is left takes the colour "
           "where it stopped")
        ->capture_default_str();
    cmd->add_flag("--reference", o->reference,
                  "Reference mode: 0.05-voxel fixed steps, no empty-space skipping, no early stop");
    addImageFlags(cmd, o->alsoPng, o->exposure);
    addStrictFlag(cmd, o->strict);
    cmd->add_option(
           "-o,--output", o->output,
           "Output .exr (linear) or .png (sRGB); numbered _000, _001... for several points")
        ->required();
    cmd->callback([o] { renderEnvmaps(*o); });
}

}  // namespace lh::cli
