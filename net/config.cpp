#include "net/config.h"

#include "core/errors.h"

#include <nlohmann/json.hpp>
#include <utility>

namespace lh::net {

// The first bundled model's sizes: a 64x48 input, half the paper's widths and 4 x 16^3 cubes,
// sigmoid colours. Kept so that models trained with it still load and run.
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

// The default: the paper's 5 x 64^3 layout from a 4:3 input of 192x144 with 32 planes. What
// makes it train on 2 CPU cores: the MPI network is 2D over the plane-sweep volume (a 3D U-Net
// over 32 x 144 x 192 costs about 10x more per iteration), and the completion networks run at
// 32^3 (8x fewer voxels than 64^3) with base width 4 (width 8 doubled the step's time:
// lighthouse_train_step_bench); the MPI's own full-resolution detail reaches the volume
// through their blend weight.
NetConfig NetConfig::standard() {
    NetConfig c;
    c.name = "standard";
    c.width = 192;
    c.height = 144;
    c.planes = 32;
    c.levels = 5;
    c.resolution = 64;
    c.baseWidth = 4;
    c.mpiNetwork = "2d";
    c.mpiWidth = 32;
    c.completionScale = 2;
    c.hdr = true;
    c.colourAnchor = true;
    c.trainEnvWidth = 120;
    c.trainEnvHeight = 60;
    c.samplesPerLevel = 48;
    return c;
}

NetConfig NetConfig::wide() {
    NetConfig c = standard();
    c.name = "wide";
    c.baseWidth = 8;
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
    c.hdr = true;
    return c;
}

NetConfig NetConfig::byName(const std::string& name) {
    // The base name, then any of the suffixes.
    std::string base = name;
    bool profile = false, emitters = false, photo = false, cells = false, apart = false,
         unclipped = false;
    for (bool found = true; found;) {
        found = false;
        for (auto [suffix, flag] : {std::pair<std::string, bool*>{"+profile", &profile},
                                    std::pair<std::string, bool*>{"+emitters", &emitters},
                                    std::pair<std::string, bool*>{"+photo", &photo},
                                    std::pair<std::string, bool*>{"+cells", &cells},
                                    std::pair<std::string, bool*>{"+apart", &apart},
                                    std::pair<std::string, bool*>{"+unclipped", &unclipped}}) {
            if (!*flag && base.size() > suffix.size() &&
                base.compare(base.size() - suffix.size(), suffix.size(), suffix) == 0) {
                base.resize(base.size() - suffix.size());
                *flag = found = true;
            }
        }
    }
    NetConfig c;
    if (base == "standard")
        c = standard();
    else if (base == "wide")
        c = wide();
    else if (base == "small")
        c = small();
    else if (base == "paper")
        c = paper();
    else
        throw InputError("unknown configuration '" + name +
                         "' (expected 'standard', 'wide', 'small' or 'paper', optionally with "
                         "'+profile', '+emitters', '+emitters+photo', then '+cells', '+apart' and "
                         "'+unclipped')");
    c.name = name;
    c.heightProfile = profile;
    c.emitters = emitters ? kSuffixEmitters : 0;
    c.emitterPhoto = photo;
    c.emitterPhotoCells = cells;
    c.emitterApart = apart;
    c.emitterPhotoUnclipped = unclipped;
    c.validate();  // "+photo" without "+emitters"; "+cells", "+apart", "+unclipped" without it
    return c;
}

void NetConfig::validate() const {
    const auto multipleOf16 = [](int v, const char* what) {
        if (v < 16 || v % 16 != 0 || v > 4096)
            throw InputError(std::string("network ") + what +
                             " must be a multiple of 16 in [16, 4096], got " + std::to_string(v));
    };
    multipleOf16(width, "input width");
    multipleOf16(height, "input height");
    multipleOf16(planes, "plane count");
    multipleOf16(resolution, "cube resolution");
    if (levels < 1 || levels > 8) throw InputError("network level count must be in [1, 8]");
    if (baseWidth < 1 || baseWidth > 64) throw InputError("network base width must be in [1, 64]");
    if (trainEnvWidth != 2 * trainEnvHeight || trainEnvHeight < 1)
        throw InputError("training envmap size must be W x H with W = 2 H");
    if (samplesPerLevel < 4 || samplesPerLevel > 1024)
        throw InputError("samples per level must be in [4, 1024]");
    if (mpiNetwork != "2d" && mpiNetwork != "3d")
        throw InputError("MPI network must be '2d' or '3d', got '" + mpiNetwork + "'");
    if (mpiWidth < 4 || mpiWidth > 256) throw InputError("MPI network width must be in [4, 256]");
    if (colourAnchor && !hdr) throw InputError("the colour anchor needs HDR colours");
    if (!(pruneAlpha >= 0 && pruneAlpha < 1))
        throw InputError("the model's pruning threshold (voxel alpha) must be in [0, 1)");
    if (!(highlightGain >= 1 && highlightGain <= kMaxHighlightGain))
        throw InputError("the model's highlight gain must be in [1, 1000]");
    if (emitters < 0 || emitters > kMaxEmitters)
        throw InputError("the emitter count must be in [0, " + std::to_string(kMaxEmitters) + "]");
    if (emitters > 0 && !hdr) throw InputError("emitters need HDR colours");
    if (emitterPhoto && emitters == 0)
        throw InputError("'+photo' is the emitter head's: it needs '+emitters'");
    if (emitterPhotoCells && !emitterPhoto)
        throw InputError("'+cells' classifies the photo head's input: it needs '+emitters+photo'");
    if (emitterApart && !emitterPhoto)
        throw InputError("'+apart' places the photo head's lamps: it needs '+emitters+photo'");
    if (emitterPhotoUnclipped && !emitterPhoto)
        throw InputError("'+unclipped' is what the photo head reads: it needs '+emitters+photo'");
    if (completionScale != 1 && completionScale != 2)
        throw InputError("completion scale must be 1 or 2");
    if (completionResolution() % 16 != 0)
        throw InputError(
            "the completion networks' resolution (cube resolution / completion scale) must be a "
            "multiple of 16");
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
                              {"samples_per_level", samplesPerLevel},
                              {"mpi_network", mpiNetwork},
                              {"mpi_width", mpiWidth},
                              {"completion_scale", completionScale},
                              {"hdr", hdr},
                              {"colour_anchor", colourAnchor},
                              {"height_profile", heightProfile},
                              {"emitters", emitters},
                              {"emitter_photo", emitterPhoto},
                              {"emitter_photo_cells", emitterPhotoCells},
                              {"emitter_apart", emitterApart},
                              {"emitter_photo_unclipped", emitterPhotoUnclipped},
                              {"prune_alpha", pruneAlpha},
                              {"highlight_gain", highlightGain}};
    return j.dump();
}

bool NetConfig::sameParameters(const NetConfig& other) const {
    // Everything but the name, the colour anchor, the pruning threshold, the highlight gain,
    // where the lamps are placed and which photo the photo head reads shapes the parameters.
    NetConfig a = *this, b = other;
    a.name = b.name;
    a.colourAnchor = b.colourAnchor;
    a.emitterApart = b.emitterApart;
    a.emitterPhotoUnclipped = b.emitterPhotoUnclipped;
    a.pruneAlpha = b.pruneAlpha;
    a.highlightGain = b.highlightGain;
    return a.toJson() == b.toJson();
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
        // Keys added after the first models: their absence means the first models' design.
        c.mpiNetwork = j.value("mpi_network", std::string("3d"));
        c.mpiWidth = j.value("mpi_width", 32);
        c.completionScale = j.value("completion_scale", 1);
        c.hdr = j.value("hdr", false);
        c.colourAnchor = j.value("colour_anchor", false);
        c.heightProfile = j.value("height_profile", false);
        c.emitters = j.value("emitters", 0);
        c.emitterPhoto = j.value("emitter_photo", false);
        c.emitterPhotoCells = j.value("emitter_photo_cells", false);
        c.emitterApart = j.value("emitter_apart", false);
        c.emitterPhotoUnclipped = j.value("emitter_photo_unclipped", false);
        c.pruneAlpha = j.value("prune_alpha", 0.0);
        c.highlightGain = j.value("highlight_gain", 1.0);
    } catch (const nlohmann::json::exception& e) {
        throw FileError(sourceName + ": network configuration is not valid: " + e.what());
    }
    c.validate();
    return c;
}

}  // namespace lh::net
