// `lighthouse render-view FILE.vdb --cameras cameras.json --view ref -o OUT.png`
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/quadrature_flags.h"
#include "core/errors.h"
#include "core/path_guard.h"
#include "render/image_io.h"
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
    QuadratureFlags quadrature;
    bool strict = false;
    std::string output;
};

void renderViewCommand(const RenderViewOptions& o) {
    if (!(o.exposure > 0.f) || !std::isfinite(o.exposure))
        throw InputError("exposure must be a positive number");
    requireOutputIsNotAnInput(o.output, "-o", {{o.file, "the input volume"}, {o.cameras, "--cameras"}});
    const CamerasFile cameras = loadCamerasFile(o.cameras);
    const PinholeCamera& camera = cameras.view(o.view);
    MarchOptions march;
    o.quadrature.applyTo(march);
    march.validate();
    const RenderVolume prepared(loadVolumeForCli(o.file, o.strict));
    writeImage(renderView(prepared, camera, march), o.output, o.exposure);
    std::cerr << "view '" << o.view << "' " << camera.width << "x" << camera.height << " -> "
              << o.output << "\n";
}

}  // namespace

void addRenderViewCommand(CLI::App& app) {
    auto o = std::make_shared<RenderViewOptions>();
    CLI::App* cmd = app.add_subcommand(
        "render-view", "Render a perspective picture of a lighting volume from a camera");
    cmd->add_option("file", o->file, "Lighting volume (.vdb)")->required();
    cmd->add_option("--cameras", o->cameras, "cameras.json (docs/conventions.md#cameras)")->required();
    cmd->add_option("--view", o->view, "Which camera: ref, src or tgt")->capture_default_str();
    cmd->add_option("--exposure", o->exposure, "PNG exposure multiplier")->capture_default_str();
    addQuadratureFlags(cmd, o->quadrature);
    cmd->add_flag("--strict", o->strict, "Refuse NaN/Inf/negative values instead of sanitising");
    cmd->add_option("-o,--output", o->output, "Output .png (sRGB) or .exr (linear)")->required();
    cmd->callback([o] { renderViewCommand(*o); });
}

}  // namespace lh::cli
