// Refusing outputs that would destroy what a command reads.
//
// An output path may name an input in many spellings: the same string, "./photo.png", a
// symlink to it, a hard link, or a file inside an input directory (an export that `import`
// reads). Writing there replaces the user's file, so every command checks its outputs against
// its inputs before it does any work.
#pragma once

#include <string>
#include <vector>

namespace lh {

// One thing a command reads: its path, and how the user gave it (for the message), e.g.
// {"photo.png", "--image"}. A directory input protects every file inside it.
struct NamedInput {
    std::string path;
    std::string option;
};

// Throws InputError "output 'OUT' (OPTION) is the input given as INPUT_OPTION ('IN'); choose
// another output path" when `output` is, or resolves to, one of `inputs`, lies inside an input
// directory, or is an existing directory that holds an input (a command that replaces its
// output directory would delete it). Inputs that do not exist are skipped (their own checks
// report them).
void requireOutputIsNotAnInput(const std::string& output, const std::string& outputOption,
                               const std::vector<NamedInput>& inputs);

// Whether two paths name the same file or directory (symlinks followed, hard links seen).
bool sameFile(const std::string& a, const std::string& b);

}  // namespace lh
