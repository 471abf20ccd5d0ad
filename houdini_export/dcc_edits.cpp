#include "houdini_export/dcc_edits.h"

#include "core/errors.h"
#include "houdini_export/grid_checksum.h"

#include <algorithm>
#include <cmath>

namespace lh {

namespace {

bool isChecksum(const nlohmann::json& v) {
    if (!v.is_string()) return false;
    const std::string s = v.get<std::string>();
    return s.size() == 16 && s.find_first_not_of("0123456789abcdef") == std::string::npos;
}

}  // namespace

std::optional<std::vector<LevelChecksums>> readManifestChecksums(const nlohmann::json& manifest,
                                                                 const std::string& manifestPath) {
    const std::string where = "'" + manifestPath + "'";
    const nlohmann::json& levels = manifest.at("levels");
    std::size_t withChecksums = 0;
    for (const auto& entry : levels)
        withChecksums += entry.is_object() && entry.contains("checksums");
    if (withChecksums == 0 && !manifest.contains("checksum")) return std::nullopt;
    if (!manifest.contains("checksum") || manifest["checksum"] != kGridChecksumMethod)
        throw FileError(where + ": \"checksum\" is " +
                        (manifest.contains("checksum") ? manifest["checksum"].dump() : "missing") +
                        ", expected \"" + kGridChecksumMethod +
                        "\" (a manifest edited by hand, or from another version)");
    if (withChecksums != levels.size())
        throw FileError(where + ": only " + std::to_string(withChecksums) + " of " +
                        std::to_string(levels.size()) +
                        " levels have \"checksums\" (a manifest edited by hand?)");
    std::vector<LevelChecksums> all;
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const nlohmann::json& c = levels[k]["checksums"];
        bool ok = c.is_object() && !c.empty();
        LevelChecksums level;
        if (ok)
            for (const auto& [name, value] : c.items()) {
                if (!isChecksum(value))
                    ok = false;
                else
                    level[name] = value.get<std::string>();
            }
        if (!ok)
            throw FileError(where + ": level " + std::to_string(k) +
                            "'s \"checksums\" is not an object of grid name -> 16 hex digits");
        all.push_back(std::move(level));
    }
    return all;
}

bool gridEdited(const LevelChecksums& checksums, const openvdb::GridBase& grid) {
    const auto it = checksums.find(grid.getName());
    return it == checksums.end() || it->second != gridChecksum(grid);
}

std::size_t disagreeingVoxels(const openvdb::FloatGrid& density, const openvdb::Vec3SGrid& emission,
                              const openvdb::Vec3SGrid& color) {
    auto e = emission.getConstAccessor();
    auto c = color.getConstAccessor();
    std::size_t n = 0;
    for (auto it = density.cbeginValueOn(); it; ++it) {
        const float sigma = *it;
        if (!(sigma > 0.f)) continue;
        if (!it.isVoxelValue()) continue;  // import voxelises tiles before it asks
        const openvdb::Vec3s em = e.getValue(it.getCoord()),
                             premultiplied = c.getValue(it.getCoord()) * sigma;
        for (int k = 0; k < 3; ++k) {
            const float larger = std::max(std::abs(em[k]), std::abs(premultiplied[k]));
            if (!(std::abs(em[k] - premultiplied[k]) <= 0.01f * larger + 1e-6f)) {
                ++n;
                break;
            }
        }
    }
    return n;
}

}  // namespace lh
