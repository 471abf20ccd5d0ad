// Subcommands of the `lighthouse` binary, one file each. Each registers itself on the app:
// it parses into an options struct and calls one library entry point. Errors propagate as
// lh::Error to main, which prints one line and returns non-zero.
#pragma once

#include <CLI/CLI.hpp>

namespace lh::cli {

void addInfoCommand(CLI::App& app);
void addRenderEnvmapCommand(CLI::App& app);
void addRenderViewCommand(CLI::App& app);
void addMakeExampleCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);
void addSynthCommand(CLI::App& app);
void addOracleCommand(CLI::App& app);
void addInsertCommand(CLI::App& app);
void addBenchEnvmapCommand(CLI::App& app);
void addSparsifyCommand(CLI::App& app);
void addShellCommand(CLI::App& app);
void addBenchSparsityCommand(CLI::App& app);
void addPhotoClippingCommand(CLI::App& app);
void addEvalDiffCommand(CLI::App& app);
void addEditCommand(CLI::App& app);
void addExportCommand(CLI::App& app);
void addImportCommand(CLI::App& app);
void addCamerasCommand(CLI::App& app);
void addMergeCommand(CLI::App& app);
// The prediction network's commands (built with libtorch only); `threads` is the global
// --threads option, read when the command runs.
void addTrainCommand(CLI::App& app, const int& threads);
void addPredictCommand(CLI::App& app, const int& threads);
void addEvalCommand(CLI::App& app, const int& threads);
void addAverageModelsCommand(CLI::App& app);

}  // namespace lh::cli
