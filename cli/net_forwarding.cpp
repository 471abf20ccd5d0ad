#include "cli/net_commands.h"

#include "cli/command_word.h"

#include "core/sibling_executable.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>

namespace lh::cli {

const char* netCommandDescription(const char* name) {
    for (const NetCommand& c : kNetCommands)
        if (std::strcmp(c.name, name) == 0) return c.description;
    return "";
}

const char* netCommandIn(int argc, char** argv) {
    const int i = commandWordIndex(argc, argv);
    if (i == 0) return nullptr;
    for (const NetCommand& c : kNetCommands)
        if (std::strcmp(argv[i], c.name) == 0) return c.name;
    return nullptr;  // the command word names another command
}

int runInNetBinary(char** argv, const char* command) {
    const SiblingExecutable net = findSiblingExecutable("lighthouse-net");
    if (!net.found) {
        std::cerr
            << "lighthouse: error: '" << command
            << "' needs the prediction network, which this build does not have (lighthouse-net "
               "was not found beside "
            << net.self << "; build with libtorch installed: see README)\n";
        return 1;
    }
    ::execv(net.path.c_str(), argv);  // returns only on failure
    std::cerr << "lighthouse: error: could not run " << net.path.string() << ": "
              << std::strerror(errno) << "\n";
    return 1;
}

void addNetCommandEntries(CLI::App& app) {
    // CLI11's --help-all expands every command but these: their options are not known here,
    // and a command's footer is not part of the expanded listing. So the main help says it.
    app.footer(
        "predict, train, eval and average-models run in lighthouse-net (libtorch): "
        "'lighthouse predict --help' (train, eval, average-models) lists their options.");
    for (const NetCommand& c : kNetCommands) {
        CLI::App* entry = app.add_subcommand(c.name, c.description);
        entry->allow_extras();
        entry->footer("Runs in lighthouse-net (libtorch); 'lighthouse " + std::string(c.name) +
                      " --help' shows its options.");
    }
}

}  // namespace lh::cli
