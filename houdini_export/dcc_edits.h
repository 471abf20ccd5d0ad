// Which grids of an export the user edited, so that `lighthouse import` honours the edit.
//
// A level file holds the radiance twice: premultiplied as emission (what the DCC renders) and
// plain as `color` / `Cd`. `lighthouse export` writes a checksum of every grid into
// manifest.json (grid_checksum.h); import recomputes them, and a grid whose checksum changed
// (or that the manifest does not list) was edited. dcc_import.h says which grid then wins.
#pragma once

#include <openvdb/openvdb.h>
#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace lh {

// One level's checksums at export: grid name -> gridChecksum.
using LevelChecksums = std::map<std::string, std::string>;

// The manifest's checksums, one entry per level in the manifest's order; nullopt if it has
// none (written before checksums existed, or by hand). Throws FileError naming `manifestPath`
// if they are malformed: another checksum method, only some levels with checksums, or an
// entry that is not grid name -> 16 hex digits.
std::optional<std::vector<LevelChecksums>> readManifestChecksums(const nlohmann::json& manifest,
                                                                 const std::string& manifestPath);

// Whether `grid` differs from what the manifest recorded for it (or is not listed there).
bool gridEdited(const LevelChecksums& checksums, const openvdb::GridBase& grid);

// Voxels of density > 0 where emission and density x colour disagree by more than 1% of the
// larger (plus 1e-6 absolute), in any channel: more than a DCC re-saving the grids at half
// precision explains (2^-11 relative per value, three values).
std::size_t disagreeingVoxels(const openvdb::FloatGrid& density, const openvdb::Vec3SGrid& emission,
                              const openvdb::Vec3SGrid& color);

}  // namespace lh
