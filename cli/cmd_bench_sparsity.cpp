// `lighthouse bench-sparsity FILE.vdb [--taus 1e-3,...] [--dataset DIR] [-o DIR] [--half]
//  [--mantissa-bits N]`:
// memory (active voxels, bytes in memory and on disk) against envmap error for several
// sparsity bounds (vdb/sparsity.h), as memory_error.csv/.md/.svg, and where the bytes in
// memory go (memory_breakdown.csv/.md). Any .vdb: oracle, predicted (dense fog: the query
// points are then the least dense ones, see render/free_space.h) or
// hand-made. With --dataset (a directory whose cameras.json lists ground-truth envmaps: a
// synthetic example or data/demo_pair) it also reports the PSNR lost against ground truth.
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "core/atomic_file.h"
#include "core/errors.h"
#include "render/envmap.h"
#include "render/render_volume.h"
#include "study/memory_error.h"
#include "vdb/mantissa_rounding.h"
#include "vdb/sparsity.h"

#include <cmath>
#include <cstdio>

#include <fstream>
#include <iostream>
#include <sstream>

namespace lh::cli {

namespace {

struct BenchSparsityOptions {
    std::string file, out = "out/sparsity", taus = "1e-4,1e-3,1e-2,1e-1,0.3,1", size = "240x120";
    MemoryErrorOptions bench;
    bool half = false;
    bool strict = false;
};

std::vector<double> parseTaus(const std::string& text) {
    std::string s = text;
    for (char& c : s)
        if (c == ',') c = ' ';
    std::istringstream in(s);
    std::vector<double> taus;
    std::string word;
    while (in >> word) {
        std::size_t used = 0;
        double tau = -1;
        try {
            tau = std::stod(word, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != word.size() || !(tau >= 0 && tau <= 1))
            throw InputError("--taus: expected numbers in [0, 1], got '" + word + "'");
        taus.push_back(tau);
    }
    if (taus.empty()) throw InputError("--taus: give at least one bound");
    return taus;
}

// Where the bytes in memory go, per setting: OpenVDB's fixed upper nodes against its 8^3
// leaves (with how full the leaves are), the renderer's own bricks (RenderVolume, built from
// the grids), and the derived bound. Re-sparsifies at every tau (cheap next to rendering).
void writeMemoryBreakdown(const LightingVolume& volume, const std::vector<double>& taus,
                          double dense, const std::string& directory) {
    std::ostringstream csv, md;
    csv << "setting,tau,levels,active_voxels,density_leaves,leaf_fill,upper_node_bytes,leaf_bytes,"
           "memory_bytes,"
           "renderer_bytes,packed_bytes_estimate,dense_bytes,ray_length,max_colour,thin_density,"
           "psnr_floor_db\n";
    md << "| setting | levels | active voxels | leaves | leaf fill | MB upper nodes | MB leaves | "
          "MB in memory | "
          "MB renderer bricks | MB packed (estimate) | thin density (/unit) | PSNR floor (dB) |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    const auto row = [&](const std::string& setting, double tau, const LightingVolume& v) {
        const MemoryBreakdown m = memoryBreakdown(v);
        const double fill =
            m.leafCount ? double(m.activeVoxels) / (double(m.leafCount) * 512) : 0.0;
        const std::size_t renderer = RenderVolume(v).memoryBytes();
        const SparsityBound b = sparsityBound(volume, std::max(tau, 0.0));
        // sRGB's slope is at most 12.92: a linear error tau is at most 12.92 tau on display.
        const double floorDb = tau > 0 ? -20 * std::log10(12.92 * tau) : 100.0;
        csv << setting << "," << tau << "," << v.levels.size() << "," << m.activeVoxels << ","
            << m.leafCount << "," << fill << "," << m.densityUpper + m.colourUpper << ","
            << m.densityLeaves + m.colourLeaves << "," << m.total() << "," << renderer << ","
            << m.packedBytes() << "," << dense << "," << b.rayLength << "," << b.maxColour << ","
            << (tau > 0 ? b.thinDensity() : 0.0) << "," << floorDb << "\n";
        char thin[32] = "-", floorText[32] = "-", line[512];
        if (tau > 0) {
            std::snprintf(thin, sizeof thin, "%.3g", b.thinDensity());
            // Above tau = 1 / 12.92 the worst case no longer bounds anything.
            if (floorDb > 0)
                std::snprintf(floorText, sizeof floorText, "%.1f", floorDb);
            else
                std::snprintf(floorText, sizeof floorText, "none");
        }
        std::snprintf(
            line, sizeof line,
            "| %s | %zu | %llu | %llu | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %s | %s |\n",
            setting.c_str(), v.levels.size(), static_cast<unsigned long long>(m.activeVoxels),
            static_cast<unsigned long long>(m.leafCount), fill,
            (m.densityUpper + m.colourUpper) / 1e6, (m.densityLeaves + m.colourLeaves) / 1e6,
            m.total() / 1e6, renderer / 1e6, m.packedBytes() / 1e6, thin, floorText);
        md << line;
    };
    row("unpruned", -1, volume);
    for (double tau : taus) {
        SparsityOptions so;
        so.tau = tau;
        std::ostringstream name;
        name << "tau " << tau;
        row(name.str(), tau, sparsify(volume, so));
    }
    writeTextFile(directory + "/memory_breakdown.csv", csv.str());
    writeTextFile(directory + "/memory_breakdown.md", md.str());
}

void runBenchSparsity(BenchSparsityOptions& o) {
    parseSize(o.size, o.bench.width, o.bench.height);
    EnvmapOptions{o.bench.width, o.bench.height, MarchOptions{}}.validate();
    o.bench.taus = parseTaus(o.taus);
    o.bench.halfPrecision = o.half;
    if (o.half && o.bench.mantissaBits > 0)
        throw InputError(
            "--half and --mantissa-bits each choose the file the pruned rows render; give one");
    validateMantissaBits(o.bench.mantissaBits, false);
    if (o.bench.points < 1 || o.bench.points > 1000)
        throw InputError("--count must be in [1, 1000]");
    const LightingVolume volume = loadVolumeForCli(o.file, o.strict);
    double dense = 0;  // bytes of the levels stored densely: sigma + RGB, 4 floats per voxel
    for (const auto& level : volume.levels)
        dense += double(level.domain.volume()) * 4 * sizeof(float);
    const auto rows = measureMemoryAgainstError(volume, o.bench, [](const std::string& s) {
        std::cerr << "bench-sparsity: " << s << "\n";
    });
    writeMemoryErrorReport(rows, o.out, dense);
    writeMemoryBreakdown(volume, o.bench.taus, dense, o.out);
    const SparsityBound b = sparsityBound(volume, 1.0);
    std::printf(
        "dense float storage: %.4g MB; bound: rays up to %.3g scene units, brightest colour %.3g, "
        "so tau "
        "drops voxels of density <= tau x %.3g per unit\n",
        dense / 1e6, b.rayLength, b.maxColour, b.thinDensity());
    std::fflush(stdout);
    std::ifstream table(o.out + "/memory_error.md"), breakdown(o.out + "/memory_breakdown.md");
    std::cout << table.rdbuf() << "\nwhere the bytes in memory go:\n" << breakdown.rdbuf();
    std::cerr << "report (csv, md, svg plot) written to " << o.out << "/\n";
}

}  // namespace

void addBenchSparsityCommand(CLI::App& app) {
    auto o = std::make_shared<BenchSparsityOptions>();
    CLI::App* cmd = app.add_subcommand(
        "bench-sparsity", "Measure memory against envmap error for several sparsity bounds");
    cmd->add_option("file", o->file, "Lighting volume (.vdb)")->required();
    cmd->add_option(
           "--taus", o->taus,
           "Comma-separated bounds: largest change of any envmap pixel, linear radiance (white 1)")
        ->capture_default_str();
    cmd->add_option("--count", o->bench.points,
                    "Random query points inside level 1's box where the medium is empty; a volume "
                    "with no empty space "
                    "(predicted fog) gets the least dense of 64 x N random points there, where a "
                    "user would put an "
                    "object")
        ->capture_default_str();
    cmd->add_option("--size", o->size, "Envmap size WxH")->capture_default_str();
    cmd->add_option("--seed", o->bench.seed, "Seed of the query points")->capture_default_str();
    cmd->add_option("--dataset", o->bench.datasetDir,
                    "Directory whose cameras.json lists ground-truth envmaps (a synthetic example, "
                    "data/demo_pair): "
                    "adds PSNR against ground truth at their points");
    cmd->add_option("-o,--output", o->out, "Directory for memory_error.csv/.md/.svg")
        ->capture_default_str();
    addHalfFlag(cmd, o->half,
                "Render the pruned volumes through half precision, as a --half file reads back");
    addMantissaBitsOption(cmd, o->bench.mantissaBits,
                          "Also store each setting with values rounded to N mantissa bits "
                          "(1-22), and render the pruned volumes from that file; 0: not");
    addStrictFlag(cmd, o->strict);
    cmd->callback([o] { runBenchSparsity(*o); });
}

}  // namespace lh::cli
