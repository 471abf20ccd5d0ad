// `lighthouse export IN.vdb --for blender|houdini -o OUT_DIR`
// Writes one .vdb per level (non-overlapping shells, the program's axes and grid names,
// values within half precision), the MPI if the volume has one, and manifest.json; see
// houdini_export/README.md.
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "core/path_guard.h"
#include "houdini_export/dcc_export.h"

#include <iostream>

namespace lh::cli {

namespace {

struct ExportOptions {
    std::string input, output, target;
    bool strict = false;
    bool force = false;
};

void runExport(const ExportOptions& o) {
    DccExportOptions options;
    options.dcc = parseDcc(o.target, "--for");
    options.replaceExisting = o.force;
    requireOutputIsNotAnInput(o.output, "-o", {{o.input, "the input volume"}});
    const VolumeFile in = loadVolumeFileForCli(o.input, o.strict);
    const DccExportReport report =
        exportForDcc(in.volume, o.output, options, in.mpi ? &*in.mpi : nullptr);
    for (const auto& w : report.warnings) std::cerr << "warning: " << w << "\n";
    const DccConvention conv = dccConvention(options.dcc);
    std::cout << o.input << " -> " << o.output << ": " << report.files.size()
              << " level file(s) for " << conv.name << " (axes " << conv.axesText << ")\n";
    for (std::size_t k = 0; k < report.files.size(); ++k)
        std::cout << "  " << report.files[k] << ": level " << k << " shell, "
                  << report.activeVoxels[k] << " active voxel(s)\n";
    if (in.mpi)
        std::cout << "  " << report.mpiFile << ": the MPI, " << in.mpi->planeCount()
                  << " plane(s) of " << in.mpi->camera.width << "x" << in.mpi->camera.height
                  << " (kept for import, not rendered)\n";
}

}  // namespace

void addExportCommand(CLI::App& app) {
    auto o = std::make_shared<ExportOptions>();
    CLI::App* cmd = app.add_subcommand("export",
                                       "Export a lighting volume for Blender or Houdini: one .vdb "
                                       "per level (non-overlapping shells) "
                                       "in the program's axes, plus manifest.json");
    cmd->add_option("input", o->input, "Lighting volume (.vdb)")->required();
    cmd->add_option("--for", o->target, "Target program: blender or houdini")->required();
    cmd->add_option("-o,--output", o->output,
                    "Export directory (created; an existing export is replaced only with --force)")
        ->required();
    cmd->add_flag("--force", o->force,
                  "Replace an existing export at --output (edits made to it are lost)");
    addStrictFlag(cmd, o->strict);
    cmd->callback([o] { runExport(*o); });
}

}  // namespace lh::cli
