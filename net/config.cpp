#include "net/config.h"

#include "core/errors.h"

#include <nlohmann/json.hpp>

namespace lh::net {

// Sized for 2 CPU cores (no oneDNN in Debian's libtorch, so 3D convolutions run as im2col +
// BLAS, whose im2col traffic dominates): a 64x48 input, half the paper's widths and
// 4 x 16^3 cubes. About 1 iteration per second with the envmap loss on this machine.
NetConfig NetConfig::small() {
    NetConfig c;
    c.name = "small";
    c.width = 64;
    c.height = 48;
    c.planes = 16;
    c.levels = 4;
    c.resolution = 16;
    c.baseWidth = 4;
    c.trainEnvWidth = 60;
    c.trainEnvHeight = 30;
    c.samplesPerLevel = 48;
    return c;
}

NetConfig NetConfig::paper() {
    NetConfig c;
    c.name = "paper";
    c.width = 320;
    c.height = 240;
    c.planes = 32;
    c.levels = 5;
    c.resolution = 64;
    c.baseWidth = 8;
    c.trainEnvWidth = 240;
    c.trainEnvHeight = 120;
    c.samplesPerLevel = 128;  // the paper's 128 spheres per level
    return c;
}

NetConfig NetConfig::byName(const std::string& name) {
    if (name == "small") return small();
    if (name == "paper") return paper();
    throw InputError("unknown configuration '" + name + "' (expected 'small' or 'paper')");
}

void NetConfig::validate() const {
    const auto multipleOf16 = [](int v, const char* what) {
        if (v < 16 || v % 16 != 0 || v > 4096)
            throw InputError(std::string("network ") + what + " must be a multiple of 16 in [16, 4096], got " +
                             std::to_string(v));
    };
    multipleOf16(width, "input width");
    multipleOf16(height, "input height");
    multipleOf16(planes, "plane count");
    multipleOf16(resolution, "cube resolution");
    if (levels < 1 || levels > 8) throw InputError("network level count must be in [1, 8]");
    if (baseWidth < 1 || baseWidth > 64) throw InputError("network base width must be in [1, 64]");
    if (trainEnvWidth != 2 * trainEnvHeight || trainEnvHeight < 1)
        throw InputError("training envmap size must be W x H with W = 2 H");
    if (samplesPerLevel < 4 || samplesPerLevel > 1024) throw InputError("samples per level must be in [4, 1024]");
}

std::string NetConfig::toJson() const {
    const nlohmann::json j = {{"name", name},
                              {"width", width},
                              {"height", height},
                              {"planes", planes},
                              {"levels", levels},
                              {"resolution", resolution},
                              {"base_width", baseWidth},
                              {"train_env_width", trainEnvWidth},
                              {"train_env_height", trainEnvHeight},
                              {"samples_per_level", samplesPerLevel}};
    return j.dump();
}

NetConfig NetConfig::fromJson(const std::string& text, const std::string& sourceName) {
    NetConfig c;
    try {
        const auto j = nlohmann::json::parse(text);
        c.name = j.at("name").get<std::string>();
        c.width = j.at("width").get<int>();
        c.height = j.at("height").get<int>();
        c.planes = j.at("planes").get<int>();
        c.levels = j.at("levels").get<int>();
        c.resolution = j.at("resolution").get<int>();
        c.baseWidth = j.at("base_width").get<int>();
        c.trainEnvWidth = j.at("train_env_width").get<int>();
        c.trainEnvHeight = j.at("train_env_height").get<int>();
        c.samplesPerLevel = j.at("samples_per_level").get<int>();
    } catch (const nlohmann::json::exception& e) {
        throw FileError(sourceName + ": network configuration is not valid: " + e.what());
    }
    c.validate();
    return c;
}

}  // namespace lh::net
