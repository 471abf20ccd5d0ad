// `lighthouse import EXPORT_DIR --from blender|houdini -o OUT.vdb`
// Reads an export (possibly edited in Blender, Houdini or python3-openvdb) back into a
// lighting volume: shells become levels, axes return to lighthouse's world frame, the edited
// radiance grid wins (houdini_export/dcc_import.h), and an exported MPI comes back too.
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "core/path_guard.h"
#include "houdini_export/dcc_import.h"
#include "vdb/volume_io.h"

#include <iostream>

namespace lh::cli {

namespace {

struct ImportOptions {
    std::string input, output, source;
    bool half = false;
    bool strict = false;
};

void runImport(const ImportOptions& o) {
    const Dcc dcc = parseDcc(o.source, "--from");
    requireVdbOutput(o.output, "the imported lighting volume");
    requireOutputIsNotAnInput(o.output, "-o", {{o.input, "the export directory"}});
    DccImportReport report;
    const LightingVolume volume = importFromDcc(
        o.input, dcc, &report, o.strict ? NonFinitePolicy::Reject : NonFinitePolicy::Sanitise);
    for (const auto& w : report.warnings) std::cerr << "warning: " << w << "\n";
    const Mpi* mpi = report.mpi ? &*report.mpi : nullptr;
    warnOfHalfClamping(saveVdb(o.output, &volume, mpi, VolumeSaveOptions{o.half}), "--half");
    std::cout << o.input << " -> " << o.output << ": " << volume.levels.size() << " level(s), "
              << volume.activeVoxelCount() << " active voxel(s)";
    if (mpi)
        std::cout << ", and the MPI (" << mpi->planeCount() << " plane(s), from " << report.mpiFile
                  << ")";
    std::cout << "\n";
    for (const auto& note : report.notes) std::cout << "  " << note << "\n";
}

}  // namespace

void addImportCommand(CLI::App& app) {
    auto o = std::make_shared<ImportOptions>();
    CLI::App* cmd = app.add_subcommand(
        "import", "Read a Blender/Houdini export (edited or not) back into a lighting volume");
    cmd->add_option("input", o->input, "Export directory written by 'lighthouse export'")
        ->required();
    cmd->add_option("--from", o->source, "Program it was exported for: blender or houdini")
        ->required();
    cmd->add_option("-o,--output", o->output, "Lighting volume (.vdb)")->required();
    addHalfFlag(cmd, o->half);
    addStrictFlag(cmd, o->strict);
    cmd->callback([o] { runImport(*o); });
}

}  // namespace lh::cli
