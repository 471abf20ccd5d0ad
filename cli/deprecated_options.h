// Old spellings of options that the command grammar (docs/cli.md) renamed. They keep working:
// the command line is rewritten to the new spelling before CLI11 parses it, with one
// "warning: OLD is deprecated; ..." line on stderr for each old spelling used. Rewriting,
// rather than a hidden second option, keeps one option per concept in each command, so that
// REQUIRED, defaults and "given twice" errors behave the same in either spelling.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace lh::cli {

// argv with the old spellings of the command's options replaced (nothing after "--" is
// touched); prints the warnings to `warnings`.
std::vector<std::string> replaceDeprecatedOptions(int argc, char** argv, std::ostream& warnings);

}  // namespace lh::cli
