// `lighthouse eval --data DIR [--model M] [-o DIR] [--shard K/N]`: the paper's Table 2 on our test
// split, with the HDR metrics of docs/metrics.md beside it.
#include "cli/commands.h"
#include "cli/net_commands.h"
#include "net/config.h"
#include "net/evaluation.h"

#include <iostream>

namespace lh::cli {

void addEvalCommand(CLI::App& app, const int& threads) {
    auto o = std::make_shared<net::EvalOptions>();
    o->hdriDir = LIGHTHOUSE_HDRI_DIR;
    o->shell = kShellByDefault;
    CLI::App* cmd = app.add_subcommand("eval", netCommandDescription("eval"));
    cmd->add_option(
           "--data", o->data,
           "Test split written by `lighthouse synth --split test`, or a set of the same layout "
           "without masks or scene.json (dev_cycles: masks from env_K_pos.exr and ref_depth.exr, "
           "no oracle row)")
        ->required();
    cmd->add_option("--model", o->model, "Model file (default: the bundled model)");
    cmd->add_option("-o,--output", o->out,
                    "Output directory: table.md, metrics.csv, contact_sheet.png, and for a model "
                    "with an emitter head lamps.csv (each lamp's angle to the nearest true lamp or "
                    "window, seen from each envmap's point)")
        ->capture_default_str();
    cmd->add_option("--max-scenes", o->maxScenes, "Evaluate only the first N scenes (0: all)")
        ->capture_default_str();
    cmd->add_flag("!--no-oracle", o->oracle,
                  "Skip the oracle ceiling (it re-bakes every scene's light)");
    cmd->add_option("--hdri-dir", o->hdriDir, "Panoramas of the scenes' windows (for the oracle)")
        ->capture_default_str();
    cmd->add_option("--prune-alpha", o->pruneAlpha,
                    "As predict's --prune-alpha (default: the model's, as predict's)")
        ->check(CLI::Range(0.0f, 1.0f));
    cmd->add_flag("--shell,!--no-shell", o->shell,
                  "As predict's --shell (the default; --no-shell scores the predicted fog as it "
                  "is)");
    cmd->add_option("--highlight-gain", o->highlightGain,
                    "As predict's --highlight-gain (default: the model's, as predict's)")
        ->check(CLI::Range(1.0, net::kMaxHighlightGain));
    cmd->add_option("--highlight-knee", o->highlightKnee, "As predict's --highlight-knee")
        ->check(CLI::Range(1.0, net::kMaxHighlightKnee))
        ->capture_default_str();
    cmd->add_flag(
        "--headroom", o->headroom,
        "Also score ours with one part of the truth put in (the observed pixels, the "
        "unobserved ones, the lamps and windows, the observed and the unobserved lamps and "
        "windows, and those unobserved ones turned 30 and 60 degrees to the side): what a "
        "perfect job on each part alone would gain; not with --shard");
    cmd->add_flag("--unclipped-photos", o->unclippedPhotos,
                  "The model reads each example's linear renders (ref.exr, src.exr) instead of "
                  "its PNG photos, as predict does given EXR photos (the MPI-only and global rows "
                  "come from the same MPI)");
    auto shard = std::make_shared<std::string>();
    cmd->add_option(
        "--shard", *shard,
        "K/N: score only scenes i with i mod N = K (0-based) into shard files in --output; "
        "`lighthouse merge` writes table.md, metrics.csv and the contact sheet of all shards");
    cmd->add_option("--device", o->device,
                    "cpu, or cuda with a CUDA build of libtorch (not yet tested on a GPU)")
        ->capture_default_str();
    cmd->callback([o, shard, &threads] {
        o->threads = threads;
        if (!shard->empty()) o->shard = parseShard(*shard);
        const net::EvalReport report = net::evaluate(*o, std::cerr);
        std::cout << report.markdown;
    });
}

}  // namespace lh::cli
