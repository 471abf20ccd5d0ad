#include "cli/deprecated_options.h"

#include "cli/command_word.h"

#include <algorithm>
#include <cstring>
#include <set>

namespace lh::cli {

namespace {

enum class Change {
    Rename,      // OLD VALUE -> NEW VALUE, OLD=VALUE -> NEW=VALUE
    Positional,  // OLD VALUE -> VALUE: the command's positional argument
    Drop,        // OLD -> nothing: it asked for what is now the default
};

struct DeprecatedOption {
    const char* command;
    const char* old;
    Change change;
    const char* replacement;  // Rename: the new option
    const char* advice;       // the end of the warning
    const char* alsoAdds;     // Rename: a flag for what the old option also did, or nullptr
};

constexpr DeprecatedOption kDeprecated[] = {
    {"synth", "--out", Change::Rename, "--output", "use -o/--output", nullptr},
    {"train", "--out", Change::Rename, "--output", "use -o/--output", nullptr},
    {"bench-envmap", "--out", Change::Rename, "--output", "use -o/--output", nullptr},
    {"bench-sparsity", "--out", Change::Rename, "--output", "use -o/--output", nullptr},
    // --points names a points file everywhere; a number of points is --count.
    {"bench-envmap", "--points", Change::Rename, "--count",
     "use --count N (--points names a points file)", nullptr},
    {"bench-sparsity", "--points", Change::Rename, "--count",
     "use --count N (--points names a points file)", nullptr},
    {"sparsify", "--points", Change::Rename, "--count",
     "use --count N (--points names a points file)", nullptr},
    // It also wrote a PNG beside each envmap, which --png asks for now.
    {"predict", "--envmap-at", Change::Rename, "--at",
     "use --at (and --png for a PNG beside each envmap)", "--png"},
    // --exposure is the PNG exposure multiplier of the commands that write images.
    {"edit", "--exposure", Change::Rename, "--scale-radiance",
     "use --scale-radiance (--exposure is the PNG multiplier of the commands that write images)",
     nullptr},
    {"insert", "--volume", Change::Positional, "",
     "give the volume as a plain argument: lighthouse insert VOLUME.vdb ...", nullptr},
    // Every command that writes values stores floats unless given --half.
    {"sparsify", "--float", Change::Drop, "", "float is the default; --half stores halves",
     nullptr},
    {"bench-sparsity", "--float", Change::Drop, "",
     "float is the default; --half renders through halves", nullptr},
    {"train", "--float-model", Change::Drop, "",
     "float32 is the default; --half writes half precision", nullptr},
};

// The entry that `arg` ("OLD" or "OLD=VALUE") spells for `command`, or nullptr.
const DeprecatedOption* find(const std::string& command, const std::string& arg) {
    for (const DeprecatedOption& d : kDeprecated) {
        const std::size_t n = std::strlen(d.old);
        if (command == d.command && arg.compare(0, n, d.old) == 0 &&
            (arg.size() == n || arg[n] == '='))
            return &d;
    }
    return nullptr;
}

}  // namespace

std::vector<std::string> replaceDeprecatedOptions(int argc, char** argv, std::ostream& warnings) {
    const std::vector<std::string> args(argv, argv + argc);
    const int at = commandWordIndex(argc, argv);
    if (at == 0) return args;
    const std::string command = args[at];
    std::vector<std::string> result(args.begin(), args.begin() + at + 1);
    std::set<const DeprecatedOption*> warned;
    for (std::size_t i = at + 1; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg == "--") {
            result.insert(result.end(), args.begin() + long(i), args.end());
            break;
        }
        const DeprecatedOption* d = find(command, arg);
        if (!d) {
            result.push_back(arg);
            continue;
        }
        if (warned.insert(d).second)
            warnings << "warning: " << d->old << " is deprecated; " << d->advice << "\n";
        const std::size_t n = std::strlen(d->old);
        const bool inlineValue = arg.size() > n;  // OLD=VALUE
        switch (d->change) {
            case Change::Rename:
                if (d->alsoAdds && std::find(args.begin(), args.end(), d->alsoAdds) == args.end() &&
                    std::find(result.begin(), result.end(), d->alsoAdds) == result.end())
                    result.push_back(d->alsoAdds);
                result.push_back(d->replacement + arg.substr(n));
                break;
            case Change::Positional:
                if (inlineValue)
                    result.push_back(arg.substr(n + 1));
                else if (i + 1 < args.size())
                    result.push_back(args[++i]);
                else
                    result.push_back(arg);  // no value: CLI11 reports the stray option
                break;
            case Change::Drop:
                break;
        }
    }
    return result;
}

}  // namespace lh::cli
