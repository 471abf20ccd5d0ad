// `lighthouse shell IN.vdb -o OUT.vdb [--centre X,Y,Z] [--half] [--mantissa-bits N]`: collapses
// a predicted volume's medium into an opaque shell as seen from one point (render/radial_shell.h),
// so that envmaps near that point render several times faster; the medium the reference camera
// saw is kept as it is. The MPI is passed on unchanged.
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "core/errors.h"
#include "core/path_guard.h"
#include "render/radial_shell.h"
#include "render/render_volume.h"
#include "vdb/mantissa_rounding.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

namespace lh::cli {

namespace {

struct ShellOptions {
    std::string input, output, centre;  // centre empty: defaultShellCentre
    bool half = false;
    int mantissaBits = 0;  // 0: values as they are
    bool strict = false;
};

void runShell(const ShellOptions& o) {
    requireVdbOutput(o.output, "the shell volume");
    requireOutputIsNotAnInput(o.output, "-o", {{o.input, "the input volume"}});
    validateMantissaBits(o.mantissaBits, o.half);
    const std::optional<Vec3d> centre =
        o.centre.empty() ? std::nullopt : std::optional<Vec3d>(parsePoint(o.centre, "--centre"));
    const VolumeFile in = loadVolumeFileForCli(o.input, o.strict);
    if (!in.volume.layout)
        throw InputError("'" + o.input +
                         "' has no nested layout (lighthouse_layout metadata): only volumes "
                         "written by predict or make-example can be collapsed into a shell");
    // A shell, marked or not, is refused with the same advice.
    const std::string collapseTheFog =
        ": collapsing it again cannot bring back the medium that shell dropped; collapse the fog "
        "of 'lighthouse predict --no-shell' instead";
    if (const std::optional<Vec3d>& done = in.volume.shellCentre) {
        char text[512];
        std::snprintf(text, sizeof text, "'%s' is already a shell, collapsed around (%g, %g, %g)%s",
                      o.input.c_str(), done->x(), done->y(), done->z(), collapseTheFog.c_str());
        throw InputError(text);
    }
    if (looksLikeUnmarkedShell(in.volume))
        throw InputError("'" + o.input +
                         "' is already a shell (every voxel outside the camera's view holds the "
                         "shell's opaque layer; it was written before shells recorded their "
                         "centre)" +
                         collapseTheFog);
    const Vec3d c = centre ? *centre : defaultShellCentre(*in.volume.layout);
    if (centre && in.volume.layout->box(0).contains(c)) {
        // Inside a wall or an object every ray from the centre stops at once, and the shell
        // wraps the centre instead of the room.
        const RenderVolume prepared(in.volume);
        const double opticalDepth = prepared.sampleWorld(c).sigma * prepared.voxelSizeAt(c);
        if (opticalDepth > std::log(2.0))
            std::cerr << "warning: --centre (" << c.x() << ", " << c.y() << ", " << c.z()
                      << ") lies inside the medium (a wall or an object), so the shell will wrap "
                         "it tightly; choose a point in the room's free space\n";
    }
    const auto start = std::chrono::steady_clock::now();
    const LightingVolume shell = collapseToShell(in.volume, c);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    warnOfHalfClamping(saveVdb(o.output, &shell, in.mpi ? &*in.mpi : nullptr,
                               VolumeSaveOptions{o.half, o.mantissaBits}),
                       "--half");
    std::printf("shell around (%g, %g, %g) in %.2f s: %llu -> %llu active voxels -> %s (%s)\n",
                c.x(), c.y(), c.z(), seconds,
                static_cast<unsigned long long>(in.volume.activeVoxelCount()),
                static_cast<unsigned long long>(shell.activeVoxelCount()), o.output.c_str(),
                keepsCameraView(in.volume, {})
                    ? "the medium the reference camera sees kept as it was"
                    : "the file has no reference camera: all of the medium collapsed");
}

}  // namespace

void addShellCommand(CLI::App& app) {
    auto o = std::make_shared<ShellOptions>();
    CLI::App* cmd = app.add_subcommand(
        "shell",
        "Collapse a predicted volume's medium into an opaque shell seen from one point: the same "
        "envmap there, several times faster envmaps around it");
    cmd->add_option("input", o->input,
                    "Lighting volume on the nested layout (.vdb): the fog of predict --no-shell, "
                    "or make-example's room; not a shell (predict's default output is one)")
        ->required();
    cmd->add_option("-o,--output", o->output, "Output .vdb")->required();
    cmd->add_option("--centre", o->centre,
                    "X,Y,Z: the point the shell is seen from, e.g. where an object will be "
                    "inserted (default: on the camera's axis, a quarter of the way into level 1, "
                    "as predict's default shell)");
    addHalfFlag(cmd, o->half);
    addMantissaBitsOption(cmd, o->mantissaBits,
                          "Round every value to N mantissa bits (1-22; 1-9 with --half) for a "
                          "smaller file; 0 keeps the values");
    addStrictFlag(cmd, o->strict);
    cmd->callback([o] { runShell(*o); });
}

}  // namespace lh::cli
