// `lighthouse sparsify IN.vdb -o OUT.vdb [--target-db 0.1] [--base-psnr 30] [--tau T]
//  [--levels-from-depth NEAR,FAR] [--half] [--mantissa-bits N]`: stores only what the scene
// needs (vdb/sparsity.h), optionally with values rounded to N mantissa bits
// (vdb/mantissa_rounding.h).
// Without --tau the bound is searched: the largest tau whose envmaps (at random free-space
// points, through the file's precision) stay within the PSNR that guarantees at most
// --target-db of loss for a volume that reaches --base-psnr against ground truth.
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "core/errors.h"
#include "core/path_guard.h"
#include "sparsify/bound_search.h"
#include "vdb/mantissa_rounding.h"
#include "vdb/sparsity.h"

#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

namespace lh::cli {

namespace {

struct SparsifyOptions {
    std::string input, output, depthRange;
    double targetDb = 0.1;  // PSNR loss allowed against ground truth, dB
    double basePsnr = 30;   // PSNR the volume reaches against ground truth, dB (higher: stricter)
    std::optional<double> tau;  // explicit bound; not given: searched from targetDb
    bool half = false;
    int mantissaBits = 0;  // 0: values as they are
    bool strict = false;
    int points = 4;  // --count
};

void runSparsify(const SparsifyOptions& o) {
    requireVdbOutput(o.output, "the sparsified volume");
    requireOutputIsNotAnInput(o.output, "-o", {{o.input, "the input volume"}});
    if (o.tau && !(*o.tau > 0))
        throw InputError(
            "--tau must be positive (a bound of 0 drops nothing; omit --tau to search for one), "
            "got " +
            std::to_string(*o.tau));
    if (o.tau) SparsityOptions{*o.tau}.validate();
    if (!(o.targetDb > 0 && o.targetDb <= 10))
        throw InputError("--target-db must be in (0, 10] dB");
    if (!(o.basePsnr > 0 && o.basePsnr < 100))
        throw InputError("--base-psnr must be in (0, 100) dB");
    if (o.points < 1 || o.points > 64) throw InputError("--count must be in [1, 64]");
    validateMantissaBits(o.mantissaBits, o.half);
    SparsityOptions options;
    if (!o.depthRange.empty()) {
        const Vec3d range = parsePoint(o.depthRange + ",1", "--levels-from-depth NEAR,FAR");
        options.maxLevels = levelsForDepthRange(range[0], range[1], 64);
    }
    const LightingVolume volume = loadVolumeForCli(o.input, o.strict);
    if (o.tau) {
        options.tau = *o.tau;
    } else {
        BoundSearchOptions search;
        search.points = o.points;
        search.halfPrecision = o.half;
        search.mantissaBits = o.mantissaBits;
        const double required = requiredPsnrForLoss(o.targetDb, o.basePsnr);
        std::fprintf(stderr, "sparsify: envmaps must stay within %.1f dB of the unpruned ones\n",
                     required);
        const BoundChoice choice = chooseSparsityBound(
            volume, required, search,
            [](const std::string& s) { std::cerr << "sparsify: " << s << "\n"; });
        options.tau = choice.tau;
    }
    SparsityStats stats;
    const LightingVolume pruned = sparsify(volume, options, &stats);
    warnOfHalfClamping(saveSparseVolume(o.output, pruned, o.half, o.mantissaBits), "--half");
    std::printf(
        "tau %.3g (rays up to %.3g scene units, brightest colour %.3g: voxels of density <= %.3g "
        "per unit "
        "dropped): %llu -> %llu active voxels, %.2f -> %.2f MB in memory, %d level(s) dropped, "
        "%s on disk (%s%s, Blosc)\n",
        options.tau, stats.rayLength, stats.maxColour,
        stats.maxColour > 0 ? stats.fieldBound / stats.maxColour : 0.0,
        static_cast<unsigned long long>(stats.activeBefore),
        static_cast<unsigned long long>(stats.activeAfter), stats.memoryBefore / 1e6,
        stats.memoryAfter / 1e6, stats.levelsDropped, o.output.c_str(), o.half ? "half" : "float",
        o.mantissaBits > 0 ? (", " + std::to_string(o.mantissaBits) + "-bit mantissas").c_str()
                           : "");
}

}  // namespace

void addSparsifyCommand(CLI::App& app) {
    auto o = std::make_shared<SparsifyOptions>();
    CLI::App* cmd = app.add_subcommand(
        "sparsify", "Drop what a volume's envmaps do not need, within an error bound");
    cmd->add_option("input", o->input, "Lighting volume (.vdb)")->required();
    cmd->add_option("-o,--output", o->output, "Output .vdb")->required();
    cmd->add_option("--target-db", o->targetDb, "PSNR loss allowed against ground truth (dB)")
        ->capture_default_str();
    cmd->add_option("--base-psnr", o->basePsnr, "PSNR the volume reaches against ground truth (dB)")
        ->capture_default_str();
    cmd->add_option("--tau", o->tau,
                    "Explicit bound in (0, 1]: largest change of any envmap pixel, linear radiance "
                    "with white = 1 (skips the search)");
    cmd->add_option("--levels-from-depth", o->depthRange,
                    "NEAR,FAR: keep the levels this depth range needs");
    cmd->add_option("--count", o->points,
                    "Random free-space points for the search (least dense points in fog)")
        ->capture_default_str();
    addHalfFlag(cmd, o->half);
    addMantissaBitsOption(cmd, o->mantissaBits,
                          "Round every value to N mantissa bits (1-22; 1-9 with --half) for a "
                          "smaller file: relative error at most 2^-(N+1), 7 = 0.4%; 0 keeps "
                          "the values");
    addStrictFlag(cmd, o->strict);
    cmd->callback([o] { runSparsify(*o); });
}

}  // namespace lh::cli
