// Where the command word is on a `lighthouse` command line. Shared by the hand-over of the
// network's commands (net_forwarding.cpp) and the rewriting of old option spellings.
#pragma once

#include <string>

namespace lh::cli {

// Index in argv of the command word: the first argument that is not an option, nor the value
// of a `--threads N` before it; 0 when there is none (or "--" comes first).
inline int commandWordIndex(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--") return 0;
        if (arg == "--threads") {
            ++i;  // its value
            continue;
        }
        if (!arg.empty() && arg[0] == '-') continue;
        return i;
    }
    return 0;
}

}  // namespace lh::cli
