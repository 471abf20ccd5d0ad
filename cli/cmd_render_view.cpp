// `lighthouse render-view FILE.vdb --cameras cameras.json --view ref -o OUT.png|OUT.exr [--png]`
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "cli/quadrature_flags.h"
#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/path_guard.h"
#include "image/image_io.h"
#include "render/render_volume.h"
#include "render/view.h"

#include <iostream>

namespace lh::cli {

namespace {

struct RenderViewOptions {
    std::string file;
    std::string cameras;
    std::string view = "ref";
    float exposure = 1.f;
    bool alsoPng = false;
    QuadratureFlags quadrature;
    bool strict = false;
    std::string output;
};

void renderViewCommand(const RenderViewOptions& o) {
    const std::string ext = fileExtension(o.output);
    if (ext != ".exr" && ext != ".png")
        throw InputError("output '" + o.output + "' must end in .exr or .png");
    requirePositiveExposure(o.exposure);
    const std::vector<NamedInput> inputs = {{o.file, "the input volume"}, {o.cameras, "--cameras"}};
    requireOutputIsNotAnInput(o.output, "-o", inputs);
    const bool png = o.alsoPng && ext == ".exr";
    if (png) requireOutputIsNotAnInput(withExtension(o.output, ".png"), "--png", inputs);
    const CamerasFile cameras = loadCamerasFile(o.cameras);
    const PinholeCamera& camera = cameras.view(o.view);
    MarchOptions march;
    o.quadrature.applyTo(march);
    march.validate();
    const RenderVolume prepared(loadVolumeForCli(o.file, o.strict));
    const ImageRGB image = renderView(prepared, camera, march);
    writeImage(image, o.output, o.exposure);
    if (png) writePng(image, withExtension(o.output, ".png"), o.exposure);
    std::cerr << "view '" << o.view << "' " << camera.width << "x" << camera.height << " -> "
              << o.output << (png ? " (+ .png)" : "") << "\n";
}

}  // namespace

void addRenderViewCommand(CLI::App& app) {
    auto o = std::make_shared<RenderViewOptions>();
    CLI::App* cmd = app.add_subcommand(
        "render-view", "Render a perspective picture of a lighting volume from a camera");
    cmd->add_option("file", o->file, "Lighting volume (.vdb)")->required();
    cmd->add_option("--cameras", o->cameras, "cameras.json (docs/conventions.md#cameras)")
        ->required();
    cmd->add_option("--view", o->view, "Which camera: ref, src or tgt")->capture_default_str();
    addImageFlags(cmd, o->alsoPng, o->exposure);
    addQuadratureFlags(cmd, o->quadrature);
    addStrictFlag(cmd, o->strict);
    cmd->add_option("-o,--output", o->output, "Output .png (sRGB) or .exr (linear)")->required();
    cmd->callback([o] { renderViewCommand(*o); });
}

}  // namespace lh::cli
