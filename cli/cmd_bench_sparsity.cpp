// `lighthouse bench-sparsity FILE.vdb [--taus 1e-4,1e-3,...] [--dataset DIR] [--out DIR]`:
// memory (active voxels, bytes in memory and on disk) against envmap error for several
// sparsity bounds (vdb/sparsity.h), as memory_error.csv/.md/.svg. Any .vdb: oracle,
// predicted or hand-made. With --dataset (a synthetic example with cameras.json and
// ground-truth envmaps) it also reports the PSNR lost against ground truth.
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "core/errors.h"
#include "render/speed_error.h"

#include <fstream>
#include <iostream>
#include <sstream>

namespace lh::cli {

namespace {

struct BenchSparsityOptions {
    std::string file, out = "out/sparsity", taus = "1e-4,1e-3,3e-3,1e-2,3e-2,1e-1", size = "240x120";
    MemoryErrorOptions bench;
    bool floatPrecision = false;
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

void runBenchSparsity(BenchSparsityOptions& o) {
    parseSize(o.size, o.bench.width, o.bench.height);
    EnvmapOptions{o.bench.width, o.bench.height, MarchOptions{}}.validate();
    o.bench.taus = parseTaus(o.taus);
    o.bench.halfPrecision = !o.floatPrecision;
    if (o.bench.points < 1 || o.bench.points > 1000) throw InputError("--points must be in [1, 1000]");
    const LightingVolume volume = loadVolumeForCli(o.file, false);
    double dense = 0;  // bytes of the levels stored densely: sigma + RGB, 4 floats per voxel
    for (const auto& level : volume.levels) dense += double(level.domain.volume()) * 4 * sizeof(float);
    const auto rows = measureMemoryAgainstError(volume, o.bench, [](const std::string& s) { std::cerr << "bench-sparsity: " << s << "\n"; });
    writeMemoryErrorReport(rows, o.out, dense);
    std::ifstream table(o.out + "/memory_error.md");
    std::cout << "dense float storage: " << dense / 1e6 << " MB\n" << table.rdbuf();
    std::cerr << "report (csv, md, svg plot) written to " << o.out << "/\n";
}

}  // namespace

void addBenchSparsityCommand(CLI::App& app) {
    auto o = std::make_shared<BenchSparsityOptions>();
    CLI::App* cmd = app.add_subcommand("bench-sparsity", "Measure memory against envmap error for several sparsity bounds");
    cmd->add_option("file", o->file, "Lighting volume (.vdb)")->required();
    cmd->add_option("--taus", o->taus, "Comma-separated bounds (display radiance per voxel)")->capture_default_str();
    cmd->add_option("--points", o->bench.points, "Random query points in empty space")->capture_default_str();
    cmd->add_option("--size", o->size, "Envmap size WxH")->capture_default_str();
    cmd->add_option("--seed", o->bench.seed, "Seed of the query points")->capture_default_str();
    cmd->add_option("--dataset", o->bench.datasetDir, "Example directory with cameras.json and ground-truth envmaps");
    cmd->add_option("--out", o->out, "Directory for memory_error.csv/.md/.svg")->capture_default_str();
    cmd->add_flag("--float", o->floatPrecision, "Render the pruned volumes in float, not through half precision");
    cmd->callback([o] { runBenchSparsity(*o); });
}

}  // namespace lh::cli
