// lighthouse: one subcommand per file. Library errors and CLI11's parse errors are caught here
// once and reported as a single line "lighthouse: error: ..." with exit status 1 (OpenVDB's
// vdb_render model); the grammar every command shares is docs/cli.md.
//
// Compiled twice: as `lighthouse`, without libtorch, which hands the network's commands to
// `lighthouse-net` (cli/net_commands.h), and, when libtorch is found, as `lighthouse-net`,
// which has every command (LIGHTHOUSE_HAS_NET).
#include "cli/commands.h"
#include "cli/deprecated_options.h"
#include "cli/net_commands.h"
#include "core/errors.h"

#include <openvdb/openvdb.h>
#include <tbb/global_control.h>

#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace {

// A CLI11 parse error (unknown option, missing value, bad value) as the one documented line,
// with the command whose --help lists the options; exit status 1. Help and --version
// (exit code 0) print what CLI11 prints.
int reportParseError(const CLI::App& app, const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::string message = e.what();
    for (char& c : message)
        if (c == '\n') c = ' ';
    const std::vector<CLI::App*> commands = app.get_subcommands();
    const std::string command = commands.empty() ? "" : " " + commands.front()->get_name();
    std::cerr << "lighthouse: error: " << message << " (run 'lighthouse" << command
              << " --help')\n";
    return 1;
}

}  // namespace

int main(int argc, char** argv) {
#ifndef LIGHTHOUSE_HAS_NET
    if (const char* command = lh::cli::netCommandIn(argc, argv))
        return lh::cli::runInNetBinary(argv, command);
#endif
    // Old option spellings become the new ones here, after the hand-over above, so that the
    // warnings are printed once, by the binary that runs the command.
    const std::vector<std::string> args = lh::cli::replaceDeprecatedOptions(argc, argv, std::cerr);
    std::vector<const char*> argp;
    for (const std::string& a : args) argp.push_back(a.c_str());

    CLI::App app{"lighthouse " LIGHTHOUSE_VERSION
                 ": predict, store and render spatially-coherent lighting volumes",
                 "lighthouse"};
    app.require_subcommand(1);
    app.set_help_all_flag("--help-all", "Show help for every command");
    app.set_version_flag("--version", "lighthouse " LIGHTHOUSE_VERSION);
    // The global options are accepted after the command word too (`lighthouse train
    // --threads 1 ...`): every command created below inherits this.
    app.fallthrough();
    int threads = 0;
    app.add_option("--threads", threads,
                   "Worker threads (default: all cores); before or after the command")
        ->check(CLI::Range(0, 1024));
    lh::cli::addInfoCommand(app);
#ifdef LIGHTHOUSE_HAS_NET
    lh::cli::addPredictCommand(app, threads);
    lh::cli::addTrainCommand(app, threads);
    lh::cli::addEvalCommand(app, threads);
    lh::cli::addAverageModelsCommand(app);
#else
    lh::cli::addNetCommandEntries(app);
#endif
    lh::cli::addRenderEnvmapCommand(app);
    lh::cli::addRenderViewCommand(app);
    lh::cli::addMakeExampleCommand(app);
    lh::cli::addCompareCommand(app);
    lh::cli::addSynthCommand(app);
    lh::cli::addOracleCommand(app);
    lh::cli::addInsertCommand(app);
    lh::cli::addEditCommand(app);
    lh::cli::addExportCommand(app);
    lh::cli::addImportCommand(app);
    lh::cli::addCamerasCommand(app);
    lh::cli::addMergeCommand(app);
    lh::cli::addBenchEnvmapCommand(app);
    lh::cli::addSparsifyCommand(app);
    lh::cli::addShellCommand(app);
    lh::cli::addBenchSparsityCommand(app);
    lh::cli::addPhotoClippingCommand(app);
    lh::cli::addEvalDiffCommand(app);

    std::unique_ptr<tbb::global_control> threadLimit;
    app.parse_complete_callback([&] {
        if (threads > 0)
            threadLimit = std::make_unique<tbb::global_control>(
                tbb::global_control::max_allowed_parallelism, threads);
    });
    // No arguments: the usage, on stdout, and exit 0 (asking for nothing is asking how).
    if (args.size() == 1) {
        std::cout << app.help();
        return 0;
    }
    try {
        // CLI11 reports a mistyped command only as "a subcommand is required": name it.
        const std::string first = args.size() > 1 ? args[1] : "";
        const auto known = [&](const CLI::App* sub) { return sub->get_name() == first; };
        if (!first.empty() && first[0] != '-' &&
            std::as_const(app).get_subcommands(known).empty()) {
            std::cerr << "lighthouse: error: unknown command '" << first
                      << "'; run 'lighthouse --help' for the list\n";
            return 1;
        }
        openvdb::initialize();
        app.parse(int(argp.size()), argp.data());
    } catch (const CLI::ParseError& e) {
        return reportParseError(app, e);
    } catch (const lh::Error& e) {
        std::cerr << "lighthouse: error: " << e.what() << "\n";
        return 1;
    } catch (const std::bad_alloc&) {
        std::cerr << "lighthouse: error: out of memory; try a smaller size or volume\n";
        return 1;
    } catch (const std::exception& e) {
        // Libraries such as libtorch append a stack trace: the first line is the message.
        const std::string message = e.what();
        std::cerr << "lighthouse: error: " << message.substr(0, message.find('\n')) << "\n";
        return 1;
    }
    return 0;
}
