#include "cli/common_options.h"

#include "core/errors.h"

#include <cmath>

namespace lh::cli {

CLI::Option* addStrictFlag(CLI::App* cmd, bool& strict) {
    return cmd->add_flag("--strict", strict,
                         "Refuse NaN/Inf/negative values in the volume instead of sanitising them");
}

CLI::Option* addMantissaBitsOption(CLI::App* cmd, int& bits, const std::string& help) {
    return cmd->add_option("--mantissa-bits", bits, help)->capture_default_str();
}

CLI::Option* addHalfFlag(CLI::App* cmd, bool& half, const std::string& help) {
    return cmd->add_flag("--half", half, help);
}

ImageFlags addImageFlags(CLI::App* cmd, bool& png, float& exposure) {
    return {cmd->add_flag("--png", png, "With an .exr output, also write an sRGB PNG beside it"),
            cmd->add_option("--exposure", exposure,
                            "Multiplier of the PNGs written (EXR keeps linear radiance)")
                ->capture_default_str()};
}

void ImageFlags::need(CLI::Option* images) const {
    png->needs(images);
    exposure->needs(images);
}

void requirePositiveExposure(float exposure) {
    if (!(exposure > 0.f) || !std::isfinite(exposure))
        throw InputError("--exposure must be a positive number, got " + std::to_string(exposure));
}

}  // namespace lh::cli
