// The options that every command spells the same way (docs/cli.md), declared here once so
// that their names, defaults and help texts cannot drift apart.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace lh::cli {

// --strict: refuse NaN, Inf and negative values in the volume read, instead of sanitising them.
CLI::Option* addStrictFlag(CLI::App* cmd, bool& strict);

// --mantissa-bits N: round every value of the written volume to N mantissa bits (lossy, a
// smaller file; vdb/mantissa_rounding.h). 0, the default, keeps the values as they are.
CLI::Option* addMantissaBitsOption(CLI::App* cmd, int& bits, const std::string& help);

// --half: store 16-bit halves instead of 32-bit floats; without it, floats. `help` says what
// is stored, when it is not a volume file.
CLI::Option* addHalfFlag(CLI::App* cmd, bool& half,
                         const std::string& help =
                             "Store 16-bit halves instead of 32-bit floats (half the "
                             "size; values above 65000 are clamped, with a warning)");

// --png (with an .exr output, also write an sRGB PNG beside it) and --exposure (multiplier of
// the PNGs written; EXR files keep linear radiance), for the commands that write images.
struct ImageFlags {
    CLI::Option* png;
    CLI::Option* exposure;
    // Where images are written only on request (an option `images`), both need it: alone,
    // they would silently do nothing.
    void need(CLI::Option* images) const;
};
ImageFlags addImageFlags(CLI::App* cmd, bool& png, float& exposure);

// Throws InputError unless `exposure` is finite and positive.
void requirePositiveExposure(float exposure);

}  // namespace lh::cli
