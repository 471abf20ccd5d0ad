// `lighthouse info FILE.vdb`: levels, boxes, voxel sizes, active voxels, memory, value ranges.
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "render/radial_shell.h"

#include <openvdb/tools/Count.h>

#include <cstdio>
#include <iostream>

namespace lh::cli {

namespace {

struct InfoOptions {
    std::string file;
    bool strict = false;
};

void printInfo(const InfoOptions& o) {
    const LightingVolume volume = loadVolumeForCli(o.file, o.strict);
    std::printf("%s: %zu level(s), %llu active voxels, %.2f MB in memory\n", o.file.c_str(),
                volume.levels.size(), (unsigned long long)volume.activeVoxelCount(),
                volume.memoryBytes() / 1e6);
    if (volume.layout)
        std::printf("layout: s0 = %g, %d levels of %d^3 voxels\n", volume.layout->s0,
                    volume.layout->levels, volume.layout->resolution);
    else
        std::printf("layout: none (levels taken from the grids as they are)\n");
    if (volume.refCamera)
        std::printf("reference camera: %dx%d, fx %.2f fy %.2f\n", volume.refCamera->width,
                    volume.refCamera->height, volume.refCamera->fx, volume.refCamera->fy);
    if (volume.shellCentre)
        std::printf(
            "shell: the medium collapsed around (%g, %g, %g) (as predict does by default; "
            "predict --no-shell writes the fog)\n",
            volume.shellCentre->x(), volume.shellCentre->y(), volume.shellCentre->z());
    else if (looksLikeUnmarkedShell(volume))
        std::printf(
            "shell: the medium collapsed around a point the file does not record (written before "
            "shells recorded it)\n");
    for (std::size_t k = 0; k < volume.levels.size(); ++k) {
        const VolumeLevel& l = volume.levels[k];
        const WorldBox box = l.worldBounds();
        const auto dim = l.domain.dim();
        const Vec3d voxel = l.transform().voxelSize();
        float dMin = 0, dMax = 0;
        if (l.density->activeVoxelCount() > 0) {
            const auto range = openvdb::tools::minMax(l.density->tree());
            dMin = range.min();
            dMax = range.max();
        }
        // Largest colour component over active voxels.
        float cMax = 0.f;
        for (auto it = l.color->cbeginValueOn(); it; ++it)
            for (int c = 0; c < 3; ++c) cMax = std::max(cMax, (*it)[c]);
        std::printf("level %zu (%s, %s, finest %s):\n", k, l.density->getName().c_str(),
                    l.color->getName().c_str(), k + 1 == volume.levels.size() ? "yes" : "no");
        std::printf("  voxels %d x %d x %d, voxel size %.4g x %.4g x %.4g\n", dim.x(), dim.y(),
                    dim.z(), voxel.x(), voxel.y(), voxel.z());
        std::printf("  world box [%.4g, %.4g] x [%.4g, %.4g] x [%.4g, %.4g]\n", box.min.x(),
                    box.max.x(), box.min.y(), box.max.y(), box.min.z(), box.max.z());
        std::printf("  active voxels %llu, memory %.2f MB\n",
                    (unsigned long long)l.density->activeVoxelCount(),
                    (l.density->memUsage() + l.color->memUsage()) / 1e6);
        std::printf("  density [%g, %g] per unit, colour max component %g\n", dMin, dMax, cMax);
    }
}

}  // namespace

void addInfoCommand(CLI::App& app) {
    auto opts = std::make_shared<InfoOptions>();
    CLI::App* cmd = app.add_subcommand("info",
                                       "Describe a lighting volume file: levels, boxes, "
                                       "voxel sizes, active voxels, memory, value ranges");
    cmd->add_option("file", opts->file, "Lighting volume (.vdb)")->required();
    addStrictFlag(cmd, opts->strict);
    cmd->callback([opts] { printInfo(*opts); });
}

}  // namespace lh::cli
