// `lighthouse bench-envmap FILE.vdb [--count 8] [--repeats 3] [--reference-step 0.05] [-o DIR]`:
// speed against error of our marcher, a fixed-step OpenVDB-sampler marcher and the paper's
// concentric spheres.
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "core/atomic_file.h"
#include "core/errors.h"
#include "render/render_volume.h"
#include "study/ray_budget.h"
#include "study/speed_error.h"

#include <fstream>
#include <iostream>

namespace lh::cli {

namespace {

struct BenchOptions {
    std::string file, out = "out/speed_error", size = "240x120";
    SpeedErrorOptions bench;
    bool strict = false;
};

void runBench(BenchOptions& o) {
    parseSize(o.size, o.bench.width, o.bench.height);
    EnvmapOptions{o.bench.width, o.bench.height, MarchOptions{}}.validate();
    if (o.bench.points < 1 || o.bench.points > 1000)
        throw InputError("--count must be in [1, 1000]");
    if (o.bench.repeats < 1 || o.bench.repeats > 100)
        throw InputError("--repeats must be in [1, 100]");
    o.bench.validate();
    const LightingVolume volume = loadVolumeForCli(o.file, o.strict);
    const auto rows = measureSpeedAgainstError(
        volume, o.bench, [](const std::string& s) { std::cerr << "bench: " << s << "\n"; });
    writeSpeedErrorReport(rows, o.out, o.bench.width, o.bench.height);
    std::ifstream table(o.out + "/speed_error.md");
    std::cout << table.rdbuf();
    // Why the fastest setting is as fast as it is: how far rays travel through medium.
    RayBudgetOptions budget;
    budget.points = o.bench.points, budget.seed = o.bench.seed;
    const std::string budgetTable =
        rayBudgetMarkdown(measureRayBudget(RenderVolume(volume), budget), budget);
    writeTextFile(o.out + "/ray_budget.md", budgetTable);
    std::cout << budgetTable;
    std::cerr << "report (csv, md, svg plot, ray_budget.md) written to " << o.out << "/\n";
}

}  // namespace

void addBenchEnvmapCommand(CLI::App& app) {
    auto o = std::make_shared<BenchOptions>();
    CLI::App* cmd = app.add_subcommand(
        "bench-envmap",
        "Measure envmap speed against error: ours, OpenVDB fixed-step, the paper's spheres");
    cmd->add_option("file", o->file, "Lighting volume (.vdb)")->required();
    cmd->add_option("--count", o->bench.points, "Random query points in empty space")
        ->capture_default_str();
    cmd->add_option("--size", o->size, "Envmap size WxH")->capture_default_str();
    cmd->add_option(
           "--methods", o->bench.methods,
           "Only these methods (reference-check, ours-steps, ours-cells, openvdb-fixed-step, "
           "paper-spheres); default: all")
        ->delimiter(',')
        ->check(CLI::IsMember({"reference-check", "ours-steps", "ours-cells", "openvdb-fixed-step",
                               "paper-spheres"}));
    cmd->add_option("--seed", o->bench.seed, "Seed of the query points")->capture_default_str();
    cmd->add_option("--repeats", o->bench.repeats,
                    "Timing rounds: each renders every setting at every point once; an envmap's "
                    "time is its fastest "
                    "round (a busy machine only adds time)")
        ->capture_default_str();
    cmd->add_option("--reference-step", o->bench.referenceStep,
                    "Step of the reference every row is measured against, in voxels (0.005-0.05; "
                    "thick steps sub-divided to an optical depth of 0.4 x it). The "
                    "reference-check row, at half of it, shows how converged it is: where that "
                    "row's error is near the others', halve the step (each halving doubles the "
                    "references' time)")
        ->capture_default_str();
    cmd->add_option("-o,--output", o->out, "Directory for speed_error.csv/.md/.svg")
        ->capture_default_str();
    addStrictFlag(cmd, o->strict);
    cmd->callback([o] { runBench(*o); });
}

}  // namespace lh::cli
