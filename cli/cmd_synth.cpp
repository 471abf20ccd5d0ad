// `lighthouse synth --seed S --count N -o DIR [--size 320x240] [--split train|test] [--shard K/N]
//  [--lamp-layout random|room]`
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "synth/dataset.h"

#include <unistd.h>

#include <cstdio>
#include <iostream>

namespace lh::cli {

namespace {

struct SynthCommandOptions {
    synth::SynthOptions synth;
    std::string size = "320x240";
    std::string envmapSize = "240x120";
    std::string shard;
    std::string lampLayout = "random";
};

std::string duration(double seconds) {
    char buf[32];
    const int s = int(seconds + 0.5);
    if (s >= 3600)
        std::snprintf(buf, sizeof buf, "%dh%02dm", s / 3600, s / 60 % 60);
    else
        std::snprintf(buf, sizeof buf, "%dm%02ds", s / 60, s % 60);
    return buf;
}

// A progress bar with ETA on a terminal; one line per example otherwise (logs, CI).
void showProgress(int done, int total, double seconds) {
    const double perExample = seconds / done;
    const int width = 30, filled = width * done / total;
    const std::string bar = std::string(filled, '#') + std::string(width - filled, '.');
    const bool tty = ::isatty(STDERR_FILENO);
    std::fprintf(stderr, "%s[%s] %d/%d examples  %.2f s/example  elapsed %s  ETA %s%s",
                 tty ? "\r" : "", bar.c_str(), done, total, perExample, duration(seconds).c_str(),
                 duration(perExample * (total - done)).c_str(), tty && done < total ? "" : "\n");
}

void runSynth(SynthCommandOptions& o) {
    parseSize(o.size, o.synth.width, o.synth.height);
    parseSize(o.envmapSize, o.synth.envWidth, o.synth.envHeight);
    if (!o.shard.empty()) o.synth.shard = parseShard(o.shard);
    o.synth.lampLayout =
        o.lampLayout == "room" ? synth::LampLayout::Room : synth::LampLayout::Random;
    o.synth.validate();
    std::cerr << "synth: " << o.synth.count << " " << o.synth.split << " examples";
    if (o.synth.shard.active)
        std::cerr << " (shard " << o.synth.shard.index << " of " << o.synth.shard.count
                  << ": examples i with i mod " << o.synth.shard.count << " = "
                  << o.synth.shard.index << ")";
    std::cerr << " of " << o.synth.width << "x" << o.synth.height << " (envmaps "
              << o.synth.envWidth << "x" << o.synth.envHeight << ") -> " << o.synth.out << "\n";
    synth::writeDataset(o.synth, showProgress);
    if (o.synth.shard.active)
        std::cerr << "wrote " << o.synth.out << "/" << o.synth.shard.recordName()
                  << "; `lighthouse merge " << o.synth.out
                  << "` writes manifest.json once every shard is done\n";
    else
        std::cerr << "wrote " << o.synth.out << "/manifest.json and contact_sheet.png\n";
}

}  // namespace

void addSynthCommand(CLI::App& app) {
    auto o = std::make_shared<SynthCommandOptions>();
    o->synth.hdriDir = LIGHTHOUSE_HDRI_DIR;
    CLI::App* cmd = app.add_subcommand(
        "synth",
        "Generate synthetic indoor scenes with exact ground truth (views, depth, envmaps, masks)");
    cmd->add_option("--seed", o->synth.seed, "Index of the first example (example i uses seed + i)")
        ->capture_default_str();
    cmd->add_option("--count", o->synth.count, "Number of examples")->capture_default_str();
    cmd->add_option("-o,--output", o->synth.out, "Output directory (one split)")->required();
    cmd->add_option("--split", o->synth.split, "train or test (disjoint seeds)")
        ->capture_default_str();
    cmd->add_option("--size", o->size, "View size WxH")->capture_default_str();
    cmd->add_option("--envmap-size", o->envmapSize, "Envmap size WxH, W = 2H")
        ->capture_default_str();
    cmd->add_option("--envmaps", o->synth.envmapsPerExample, "Ground-truth envmaps per example")
        ->capture_default_str();
    cmd->add_option("--supersample", o->synth.supersample, "Rays per pixel and axis")
        ->capture_default_str();
    cmd->add_option("--texel", o->synth.bake.texelSize, "Irradiance texel size, metres")
        ->capture_default_str();
    cmd->add_option("--gather", o->synth.bake.gatherRays, "Gather rays per texel")
        ->capture_default_str();
    cmd->add_option(
           "--oracle-levels", o->synth.oracleLevels,
           "Also write each example's oracle volume (oracle.vdb) with this many levels (0: none); "
           "the target of train's voxel supervision")
        ->capture_default_str();
    cmd->add_option("--oracle-res", o->synth.oracleResolution,
                    "Voxels per side of each oracle level")
        ->capture_default_str();
    cmd->add_option(
        "--shard", o->shard,
        "K/N: write only examples i with i mod N = K (0-based) and a shard record; several shards "
        "share one --output, and `lighthouse merge` writes manifest.json and the contact sheet");
    cmd->add_option("--lamp-layout", o->lampLayout,
                    "Where the ceiling lights go: random (anywhere on the ceiling) or room (evenly "
                    "along the middle of the ceiling, as real rooms are lit; the same scenes "
                    "otherwise)")
        ->check(CLI::IsMember({"random", "room"}))
        ->capture_default_str();
    cmd->add_option("--hdri-dir", o->synth.hdriDir,
                    "Folder of equirectangular .exr panoramas for windows")
        ->capture_default_str();
    cmd->callback([o] { runSynth(*o); });
}

}  // namespace lh::cli
