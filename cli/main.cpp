// lighthouse: one subcommand per file. Library errors are caught here once and reported as a
// single line with a non-zero exit (OpenVDB's vdb_render model).
//
// Compiled twice: as `lighthouse`, without libtorch, which hands the network's commands to
// `lighthouse-net` (cli/net_commands.h), and, when libtorch is found, as `lighthouse-net`,
// which has every command (LIGHTHOUSE_HAS_NET).
#include "cli/commands.h"
#include "cli/net_commands.h"
#include "core/errors.h"

#include <openvdb/openvdb.h>
#include <tbb/global_control.h>

#include <iostream>
#include <memory>
#include <string>
#include <utility>

int main(int argc, char** argv) {
#ifndef LIGHTHOUSE_HAS_NET
    if (const char* command = lh::cli::netCommandIn(argc, argv)) return lh::cli::runInNetBinary(argv, command);
#endif
    CLI::App app{"lighthouse: predict, store and render spatially-coherent lighting volumes"};
    app.require_subcommand(1);
    app.set_help_all_flag("--help-all", "Show help for every command");
    int threads = 0;
    app.add_option("--threads", threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(0, 1024));
    lh::cli::addInfoCommand(app);
#ifdef LIGHTHOUSE_HAS_NET
    lh::cli::addPredictCommand(app, threads);
    lh::cli::addTrainCommand(app, threads);
    lh::cli::addEvalCommand(app, threads);
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
    lh::cli::addBenchSparsityCommand(app);

    std::unique_ptr<tbb::global_control> threadLimit;
    app.parse_complete_callback([&] {
        if (threads > 0)
            threadLimit = std::make_unique<tbb::global_control>(
                tbb::global_control::max_allowed_parallelism, threads);
    });
    try {
        // CLI11 reports a mistyped command only as "a subcommand is required": name it.
        const std::string first = argc > 1 ? argv[1] : "";
        const auto known = [&](const CLI::App* sub) { return sub->get_name() == first; };
        if (!first.empty() && first[0] != '-' &&
            std::as_const(app).get_subcommands(known).empty()) {
            std::cerr << "lighthouse: error: unknown command '" << argv[1]
                      << "'; run 'lighthouse --help' for the list\n";
            return 1;
        }
        openvdb::initialize();
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
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
