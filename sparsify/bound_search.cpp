#include "sparsify/bound_search.h"

#include "core/errors.h"
#include "render/free_space.h"
#include "sparsify/envmap_error.h"
#include "vdb/sparsity.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace lh {

double requiredPsnrForLoss(double lossDb, double basePsnr) {
    if (!(lossDb > 0 && std::isfinite(lossDb) && std::isfinite(basePsnr)))
        throw InputError("a PSNR loss target must be positive, got " + std::to_string(lossDb));
    return basePsnr - 20.0 * std::log10(std::pow(10.0, lossDb / 20.0) - 1.0);
}

BoundChoice chooseSparsityBound(const LightingVolume& volume, double requiredPsnr,
                                const BoundSearchOptions& o,
                                const std::function<void(const std::string&)>& progress) {
    const RenderVolume unprunedRender(volume);
    const std::vector<Vec3d> points = freeSpacePoints(unprunedRender, o.points, o.seed);
    const std::vector<ImageRGB> reference =
        renderEnvmapsAt(unprunedRender, points, o.width, o.height, nullptr, o.errorMarch);
    const std::string scratch = scratchDirectory(o.scratchDir);
    BoundChoice choice;
    for (double tau = 0.1; tau > 0.9e-6; tau /= std::sqrt(10.0)) {
        SparsityOptions so;
        so.tau = tau;
        const LightingVolume pruned = sparsify(volume, so);
        const bool stored = o.halfPrecision || o.mantissaBits > 0;
        const RenderVolume render(
            stored ? asStored(pruned, o.halfPrecision, scratch, nullptr, o.mantissaBits) : pruned);
        const EnvmapSetError e = compareEnvmapSets(
            renderEnvmapsAt(render, points, o.width, o.height, nullptr, o.errorMarch), reference);
        if (progress) {
            char line[128];
            std::snprintf(line, sizeof line, "tau %.3g: %.1f dB against the unpruned envmaps", tau,
                          e.psnr);
            progress(line);
        }
        if (e.psnr >= requiredPsnr) {
            choice = {tau, e.psnr};
            break;
        }
    }
    std::filesystem::remove_all(scratch);
    return choice;
}

}  // namespace lh
