// `lighthouse make-example -o example.vdb [--cameras cameras.json]`: the bundled example room,
// built by code (vdb/example_volume.h), for demos and tests.
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "core/atomic_file.h"
#include "core/errors.h"
#include "vdb/example_volume.h"
#include "vdb/volume_io.h"

#include <fstream>
#include <iostream>
#include <memory>

namespace lh::cli {

namespace {

struct MakeExampleOptions {
    std::string output;
    std::string cameras;
    int levels = 5;
    int resolution = 64;
    bool half = false;
};

void makeExample(const MakeExampleOptions& o) {
    requireVdbOutput(o.output, "the example lighting volume");
    VolumeLayout::fromFarDepth(7.0, o.levels, o.resolution);  // validates before any work
    // The cameras file is written to its temporary first, so that a bad cameras path fails
    // before the volume exists; both appear only if both succeed.
    std::unique_ptr<AtomicOutput> cameras;
    if (!o.cameras.empty()) {
        cameras = std::make_unique<AtomicOutput>(o.cameras);
        std::ofstream f(cameras->tempPath());
        f << camerasToJson(exampleCameras()) << "\n";
        if (!f) throw FileError("cannot write '" + o.cameras + "'");
    }
    const LightingVolume volume = makeExampleVolume(o.levels, o.resolution);
    warnOfHalfClamping(saveVolume(o.output, volume, VolumeSaveOptions{o.half}), "--half");
    std::cerr << "example room: " << volume.levels.size() << " levels of " << o.resolution << "^3, "
              << volume.activeVoxelCount() << " active voxels -> " << o.output << "\n";
    if (cameras) {
        cameras->commit();
        std::cerr << "cameras -> " << o.cameras << "\n";
    }
}

}  // namespace

void addMakeExampleCommand(CLI::App& app) {
    auto o = std::make_shared<MakeExampleOptions>();
    CLI::App* cmd = app.add_subcommand(
        "make-example", "Write the bundled example lighting volume (a procedural room)");
    cmd->add_option("-o,--output", o->output, "Output .vdb")->required();
    cmd->add_option("--cameras", o->cameras, "Also write the example's cameras.json here");
    cmd->add_option("--levels", o->levels, "Number of nested levels")->capture_default_str();
    cmd->add_option("--res", o->resolution, "Voxels per side of every level")
        ->capture_default_str();
    addHalfFlag(cmd, o->half);
    cmd->callback([o] { makeExample(*o); });
}

}  // namespace lh::cli
