// `lighthouse import EXPORT_DIR --from blender|houdini -o OUT.vdb`
// Reads an export (possibly edited in Blender, Houdini or python3-openvdb) back into a
// lighting volume: shells become levels, axes return to lighthouse's world frame.
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
};

void runImport(const ImportOptions& o) {
    const Dcc dcc = parseDcc(o.source, "--from");
    requireOutputIsNotAnInput(o.output, "-o", {{o.input, "the export directory"}});
    std::vector<std::string> warnings;
    const LightingVolume volume = importFromDcc(o.input, dcc, &warnings);
    for (const auto& w : warnings) std::cerr << "warning: " << w << "\n";
    warnOfHalfClamping(saveVolume(o.output, volume, VolumeSaveOptions{o.half}), "--half");
    std::cout << o.input << " -> " << o.output << ": " << volume.levels.size() << " level(s), "
              << volume.activeVoxelCount() << " active voxel(s)\n";
}

}  // namespace

void addImportCommand(CLI::App& app) {
    auto o = std::make_shared<ImportOptions>();
    CLI::App* cmd = app.add_subcommand(
        "import", "Read a Blender/Houdini export (edited or not) back into a lighting volume");
    cmd->add_option("input", o->input, "Export directory written by 'lighthouse export'")->required();
    cmd->add_option("--from", o->source, "Program it was exported for: blender or houdini")->required();
    cmd->add_option("-o,--output", o->output, "Lighting volume (.vdb)")->required();
    addHalfFlag(cmd, o->half);
    cmd->callback([o] { runImport(*o); });
}

}  // namespace lh::cli
