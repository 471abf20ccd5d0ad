// The prediction network's commands (train, predict, eval) live in a second executable,
// `lighthouse-net`, built beside `lighthouse` when libtorch is found. Loading libtorch costs
// ~0.9 s and ~150 MB at every start, which `lighthouse render-envmap`, `info` and the other
// commands have no use for; so `lighthouse` does not link it, lists the network's commands in
// its help, and hands a command line that names one to `lighthouse-net` unchanged (exec).
#pragma once

#include <CLI/CLI.hpp>

namespace lh::cli {

struct NetCommand {
    const char* name;
    const char* description;
};
// Shared by the real commands (cmd_train.cpp, ...) and the entries in `lighthouse --help`.
inline constexpr NetCommand kNetCommands[] = {
    {"predict", "Predict a lighting volume (MPI + completed levels) from a stereo pair"},
    {"train", "Train the prediction network on a synthetic data set (resumes from OUT.checkpoint)"},
    {"eval",
     "Score the model against baselines and the oracle on a synthetic test split (Markdown table + "
     "contact sheet)"},
    {"average-models",
     "Average the weights of models fine-tuned from one model (a model soup): one model file"},
};
const char* netCommandDescription(const char* name);

// Whether predict and eval collapse the medium the camera did not see into a shell when neither
// --shell nor --no-shell is given (docs/network.md, "The shell"). The library's options keep the
// fog by default, so that tests and benchmarks of the network measure what it predicts.
inline constexpr bool kShellByDefault = true;

// The network command a command line runs (its command word, cli/command_word.h), or
// nullptr. `--threads N` may come before or after it: both are handed over as they are.
const char* netCommandIn(int argc, char** argv);

// Replaces this process by `lighthouse-net` beside this executable, with the same arguments.
// Returns only if that fails: prints one error line and returns the exit status (1).
int runInNetBinary(char** argv, const char* command);

// Entries for the network's commands in `lighthouse --help` (never parsed: a command line
// that names one is handed over before parsing).
void addNetCommandEntries(CLI::App& app);

}  // namespace lh::cli
