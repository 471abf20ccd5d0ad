#include "houdini_export/dcc_import.h"

#include "core/errors.h"
#include "houdini_export/dcc_edits.h"
#include "houdini_export/shells.h"
#include "vdb/safe_read.h"
#include "vdb/volume_io.h"

#include <openvdb/io/File.h>
#include <openvdb/tools/Prune.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>

namespace fs = std::filesystem;

namespace lh {

namespace {

nlohmann::json readManifest(const fs::path& dir, const DccConvention& conv) {
    const std::string where = "'" + dir.string() + "'";
    if (!fs::exists(dir)) throw FileError(where + " does not exist");
    if (!fs::is_directory(dir))
        throw FileError(
            where +
            " is not an export directory (run 'lighthouse export' first; it writes a directory)");
    const fs::path path = dir / kDccManifestName;
    if (!fs::is_regular_file(path))
        throw FileError(where + " is not a lighthouse export: it has no " +
                        std::string(kDccManifestName));
    nlohmann::json m;
    try {
        std::ifstream in(path);
        m = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
        throw FileError("'" + path.string() + "' is not valid JSON (" + e.what() + ")");
    }
    if (!m.is_object() || !m.contains("lighthouse_export") ||
        !m["lighthouse_export"].is_number_integer())
        throw FileError("'" + path.string() + "' is not a lighthouse export manifest");
    if (m["lighthouse_export"].get<int>() > kDccExportVersion)
        throw FileError("'" + path.string() + "' is export version " +
                        std::to_string(m["lighthouse_export"].get<int>()) +
                        "; this build reads up to " + std::to_string(kDccExportVersion));
    if (!m.contains("for") || !m["for"].is_string() || m["for"].get<std::string>() != conv.name)
        throw FileError(
            where + " was exported for '" +
            (m.contains("for") && m["for"].is_string() ? m["for"].get<std::string>() : "?") +
            "', not for '" + conv.name + "'");
    if (!m.contains("levels") || !m["levels"].is_array() || m["levels"].empty())
        throw FileError("'" + path.string() + "' lists no levels");
    return m;
}

// The export id the manifest gives its files ("" for a manifest written before ids existed).
std::string manifestExportId(const nlohmann::json& manifest, const fs::path& manifestPath) {
    if (!manifest.contains("export_id")) return "";
    if (!manifest["export_id"].is_string() || manifest["export_id"].get<std::string>().empty())
        throw FileError("'" + manifestPath.string() + "': \"export_id\" is not a string");
    return manifest["export_id"].get<std::string>();
}

struct LevelFile {
    openvdb::GridPtrVec grids;
    openvdb::MetaMap::Ptr meta;
};

LevelFile readGrids(const std::string& path) {
    if (!fs::is_regular_file(path)) throw FileError("'" + path + "' is missing from the export");
    probeVdbReadable(path);
    try {
        openvdb::io::File file(path);
        file.open(false);
        LevelFile contents{*file.getGrids(), file.getMetadata()};
        file.close();
        return contents;
    } catch (const openvdb::Exception& e) {
        throw FileError("'" + path + "' is not a readable VDB file (" + e.what() + ")");
    }
}

// A file that carries another export's id does not belong with this manifest (a program that
// drops file metadata on saving leaves no id, and is not blamed).
void requireSameExport(const openvdb::MetaMap& meta, const std::string& exportId,
                       const std::string& path, const fs::path& manifestPath) {
    const auto id = meta.getMetadata<openvdb::StringMetadata>("lighthouse_export_id");
    if (exportId.empty() || !id || id->value() == exportId) return;
    throw FileError("'" + path + "' belongs to another export than '" + manifestPath.string() +
                    "' (export id " + id->value() + ", the manifest's " + exportId +
                    "): put back the files that were exported together, or export again");
}

template <typename GridT>
typename GridT::Ptr findGrid(const openvdb::GridPtrVec& grids, const std::string& name,
                             const std::string& path, const char* expected, bool required) {
    for (const auto& g : grids) {
        if (g->getName() != name) continue;
        auto typed = openvdb::gridPtrCast<GridT>(g);
        if (!typed)
            throw FileError("'" + path + "': grid '" + name + "' is " + gridKind(*g) +
                            ", expected " + expected);
        if (!g->transform().isLinear())
            throw FileError("'" + path + "': grid '" + name +
                            "' has a non-affine (frustum) transform");
        return typed;
    }
    if (required) throw FileError("'" + path + "' has no grid '" + name + "' (" + expected + ")");
    return nullptr;
}

// The NaN, +Inf and negative values met in one grid, counted as loadVolume counts them.
struct BadValues {
    std::size_t nan = 0, posInf = 0, negative = 0;
    std::size_t total() const { return nan + posInf + negative; }
    std::string text() const {
        return std::to_string(nan) + " NaN, " + std::to_string(posInf) + " +Inf, " +
               std::to_string(negative) + " negative value(s)";
    }
};

// NaN -> 0, +Inf -> big, negative (-Inf too) -> 0, counted in `bad`.
void sanitise(float& v, float big, BadValues& bad) {
    if (std::isnan(v))
        v = 0.f, ++bad.nan;
    else if (v < 0.f)
        v = 0.f, ++bad.negative;
    else if (std::isinf(v))
        v = big, ++bad.posInf;
}

openvdb::CoordBBox storedDomain(const openvdb::GridBase& grid) {
    auto lo = grid.getMetadata<openvdb::Vec3IMetadata>("lighthouse_domain_min");
    auto hi = grid.getMetadata<openvdb::Vec3IMetadata>("lighthouse_domain_max");
    if (lo && hi)
        return openvdb::CoordBBox(openvdb::Coord(lo->value()), openvdb::Coord(hi->value()));
    return openvdb::CoordBBox();
}

openvdb::Mat4d inverseRotationAsMat4(const Mat3d& r) {
    // Row-vector convention (v' = v M): the inverse rotation R^T enters as (R^T)^T = R.
    openvdb::Mat4d m = openvdb::Mat4d::identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[i][j] = r[i][j];
    return m;
}

struct LevelRead {
    VolumeLevel level;
    std::string path;
};

// Where a level's radiance comes from: the emission grid(s) (colour = emission / density) or
// the colour grid. See dcc_import.h.
struct RadianceChoice {
    bool fromEmission = true;
    std::string note, warning;  // for the report, "" when there is nothing to say
};

RadianceChoice chooseRadiance(const std::string& path, int k, const DccConvention& conv,
                              const openvdb::FloatGrid& density,
                              const openvdb::Vec3SGrid::Ptr& emission,
                              const openvdb::GridPtrVec& emissionGrids,
                              const openvdb::Vec3SGrid::Ptr& color,
                              const LevelChecksums* checksums) {
    if (!emission) return {false, "", ""};
    if (!color || !checksums) return {};
    bool emissionEdited = false;
    for (const auto& g : emissionGrids) emissionEdited |= gridEdited(*checksums, *g);
    const std::string level = " (level " + std::to_string(k) + ")";
    const std::string e = "'" + emission->getName() + "'", c = "'" + conv.colorGrid + "'";
    if (!gridEdited(*checksums, *color)) return {};
    if (!emissionEdited)
        return {false,
                "'" + path + "'" + level + ": " + c + " was edited, " + e +
                    " was not: radiance from " + c,
                ""};
    const std::size_t disagree = disagreeingVoxels(density, *emission, *color);
    if (disagree == 0) return {};
    return {true, "",
            "'" + path + "'" + level + ": both " + c + " and " + e +
                " were edited, and they disagree in " + std::to_string(disagree) +
                " voxel(s) (emission != density x " + conv.colorGrid + "); radiance from " + e +
                ", what the renderer showed: make them agree, or undo one edit"};
}

LevelRead readLevel(const std::string& path, int k, const DccConvention& conv,
                    const LevelChecksums* checksums, const std::string& exportId,
                    const fs::path& manifestPath, NonFinitePolicy policy,
                    std::vector<std::string>& warnings, std::vector<std::string>& notes) {
    const LevelFile file = readGrids(path);
    requireSameExport(*file.meta, exportId, path, manifestPath);
    const openvdb::GridPtrVec& grids = file.grids;
    auto density = findGrid<openvdb::FloatGrid>(grids, kDccDensityGrid, path,
                                                "a FloatGrid (extinction density)", true);
    auto emission = findGrid<openvdb::Vec3SGrid>(grids, kDccEmissionGrid, path,
                                                 "a Vec3SGrid (sigma * radiance)", false);
    auto color = findGrid<openvdb::Vec3SGrid>(grids, conv.colorGrid, path,
                                              "a Vec3SGrid (linear radiance)", false);
    // Blender's three float channels, merged into one Vec3SGrid (they are what Cycles rendered).
    openvdb::FloatGrid::Ptr channel[3];
    for (int c = 0; c < 3; ++c)
        channel[c] =
            findGrid<openvdb::FloatGrid>(grids, kDccEmissionChannelGrids[c], path,
                                         "a FloatGrid (sigma * radiance, one channel)", false);
    openvdb::GridPtrVec emissionGrids;  // as read, for their checksums
    if (emission) emissionGrids.push_back(emission);
    if (channel[0] || channel[1] || channel[2]) {
        if (!(channel[0] && channel[1] && channel[2]))
            throw FileError("'" + path + "' has only some of emission_r, emission_g, emission_b");
        emissionGrids.assign(channel, channel + 3);
        emission = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
        emission->setName("emission_r/g/b");
        for (int c = 0; c < 3; ++c) {
            if (channel[c]->transform() != density->transform())
                throw FileError("'" + path + "': grids 'density' and '" + channel[c]->getName() +
                                "' have different transforms; resample one onto the other");
            channel[c]->tree().voxelizeActiveTiles();
            auto acc = emission->getAccessor();
            for (auto it = channel[c]->cbeginValueOn(); it; ++it) {
                openvdb::Vec3s v = acc.getValue(it.getCoord());
                v[c] = *it;
                acc.setValueOn(it.getCoord(), v);
            }
        }
        emission->setTransform(density->transform().copy());
    }
    if (!emission && !color)
        throw FileError("'" + path + "' has neither an '" + kDccEmissionGrid + "' nor a '" +
                        conv.colorGrid + "' grid");
    density->tree().voxelizeActiveTiles();
    const RadianceChoice choice =
        chooseRadiance(path, k, conv, *density, emission, emissionGrids, color, checksums);
    if (!choice.note.empty()) notes.push_back(choice.note);
    if (!choice.warning.empty()) warnings.push_back(choice.warning);
    const bool premultiplied = choice.fromEmission;
    auto radianceSource = premultiplied ? emission : color;
    if (radianceSource->transform() != density->transform())
        throw FileError("'" + path + "': grids 'density' and '" + radianceSource->getName() +
                        "' have different transforms; resample one onto the other");
    radianceSource->tree().voxelizeActiveTiles();

    VolumeLevel level;
    level.density = openvdb::FloatGrid::create(0.f);
    level.color = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    auto d = level.density->getAccessor();
    auto c = level.color->getAccessor();
    auto src = radianceSource->getConstAccessor();
    std::size_t emissionWithoutDensity = 0;
    BadValues badDensity, badRadiance;
    for (auto it = density->cbeginValueOn(); it; ++it) {
        float sigma = *it;
        sanitise(sigma, kOpaqueDensity, badDensity);
        if (!(sigma > 0.f)) continue;
        openvdb::Vec3s rgb = src.getValue(it.getCoord());
        for (int ch = 0; ch < 3; ++ch)
            sanitise(rgb[ch], premultiplied ? kMaxRadiance * sigma : kMaxRadiance, badRadiance);
        if (premultiplied) rgb = rgb / sigma;
        d.setValueOn(it.getCoord(), sigma);
        c.setValueOn(it.getCoord(), rgb);
    }
    auto dAcc = density->getConstAccessor();
    for (auto it = radianceSource->cbeginValueOn(); it; ++it) {
        const openvdb::Vec3s v = *it;
        if (!(dAcc.getValue(it.getCoord()) > 0.f) && (v[0] > 0 || v[1] > 0 || v[2] > 0))
            ++emissionWithoutDensity;
    }
    if (policy == NonFinitePolicy::Reject)
        for (const auto& [grid, bad] : {std::pair{density->getName(), badDensity},
                                        std::pair{radianceSource->getName(), badRadiance}})
            if (bad.total())
                throw FileError("'" + path + "': grid '" + grid + "' holds " + bad.text());
    if (const std::size_t fixedValues = badDensity.total() + badRadiance.total())
        warnings.push_back(
            "'" + path + "': replaced " + std::to_string(fixedValues) +
            " NaN/Inf/negative value(s) (NaN -> 0, +Inf -> opaque/max, negative -> 0)");
    if (emissionWithoutDensity)
        warnings.push_back(
            "'" + path + "': " + std::to_string(emissionWithoutDensity) + " voxel(s) of '" +
            radianceSource->getName() +
            "' glow where density is 0; a lighting volume emits only where it has density, so "
            "they were dropped (give them density)");
    auto xf = density->transform().copy();
    xf->postMult(inverseRotationAsMat4(conv.worldToDcc));
    if (conv.indexShift != 0.0) xf->preTranslate(Vec3d(-conv.indexShift));
    level.density->setTransform(xf);
    level.color->setTransform(xf->copy());
    level.density->setName(densityGridName(0));
    level.color->setName(colorGridName(0));
    level.domain = storedDomain(*density);
    return {level, path};
}

// The export's MPI (dcc_export.h): planes and the camera in lighthouse's frame; the planes'
// transforms, in the program's axes, are not needed to rebuild it.
Mpi readMpi(const std::string& path, const std::string& exportId, const fs::path& manifestPath) {
    const LevelFile file = readGrids(path);
    requireSameExport(*file.meta, exportId, path, manifestPath);
    const auto camera = file.meta->getMetadata<openvdb::StringMetadata>("lighthouse_mpi_camera");
    if (!camera)
        throw FileError("'" + path + "' holds no MPI (no 'lighthouse_mpi_camera' metadata)");
    return mpiFromGrids(file.grids, cameraFromJson(camera->value(), path), "'" + path + "'");
}

// A file the manifest names, as a path inside the export directory.
fs::path fileInExport(const nlohmann::json& entry, const fs::path& dir, const char* what) {
    const fs::path manifestPath = dir / kDccManifestName;
    if (!entry.is_object() || !entry.contains("file") || !entry["file"].is_string())
        throw FileError("'" + manifestPath.string() + "': " + what + " entry has no \"file\"");
    const std::string file = entry["file"].get<std::string>();
    if (file.find('/') != std::string::npos || file == ".." || file == "." || file.empty())
        throw FileError("'" + manifestPath.string() + "': file '" + file +
                        "' must be a plain name inside the export directory");
    return dir / file;
}

}  // namespace

LightingVolume importFromDcc(const std::string& dirText, Dcc dcc, DccImportReport* reportOut,
                             NonFinitePolicy nonFinite) {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
    DccImportReport report;
    std::vector<std::string>& warnings = report.warnings;
    const DccConvention conv = dccConvention(dcc);
    const fs::path dir(dirText);
    const fs::path manifestPath = dir / kDccManifestName;
    const nlohmann::json manifest = readManifest(dir, conv);
    const std::string exportId = manifestExportId(manifest, manifestPath);
    const auto checksums = readManifestChecksums(manifest, manifestPath.string());
    if (!checksums)
        warnings.push_back(
            "'" + manifestPath.string() +
            "' has no grid checksums (an export by an older lighthouse, or a hand-made manifest): "
            "the radiance comes from the emission grid(s) wherever they exist, so an edit to '" +
            conv.colorGrid + "' alone is ignored; export again to have either edit honoured");

    std::vector<LevelRead> reads;
    for (std::size_t k = 0; k < manifest["levels"].size(); ++k) {
        const fs::path path = fileInExport(manifest["levels"][k], dir, "a level");
        reads.push_back(readLevel(path.string(), int(k), conv,
                                  checksums ? &(*checksums)[k] : nullptr, exportId, manifestPath,
                                  nonFinite, warnings, report.notes));
    }
    LightingVolume volume;
    for (auto& r : reads) volume.levels.push_back(r.level);
    try {
        volume.normaliseLevels();
    } catch (const InputError& e) {
        throw FileError("'" + dirText + "': " + e.what());
    }
    // Reorder the paths the same way (normaliseLevels sorts by voxel volume, coarsest first).
    std::sort(reads.begin(), reads.end(), [](const LevelRead& a, const LevelRead& b) {
        return a.level.voxelVolume() > b.level.voxelVolume();
    });

    // Domains: stored ones, else the active box; the coarsest also covers all its content.
    for (std::size_t k = 0; k < volume.levels.size(); ++k) {
        VolumeLevel& level = volume.levels[k];
        const openvdb::CoordBBox active = level.density->evalActiveVoxelBoundingBox();
        if (level.domain.empty())
            level.domain = active;
        else if (k == 0 && !active.empty())
            level.domain.expand(active);
        if (level.domain.empty())
            throw FileError("'" + reads[k].path +
                            "' is empty and has no lighthouse_domain metadata: "
                            "its level's extent is unknown");
    }
    // Content finest-wins would hide: outside a finer level's domain, or under a finer level.
    for (std::size_t k = 0; k < volume.levels.size(); ++k) {
        VolumeLevel& level = volume.levels[k];
        std::size_t outside = 0, covered = 0;
        std::vector<openvdb::Coord> drop;
        for (auto it = level.density->cbeginValueOn(); it; ++it) {
            if (!level.domain.isInside(it.getCoord()))
                ++outside, drop.push_back(it.getCoord());
            else if (finestLevelAt(volume, level.transform().indexToWorld(it.getCoord())) != int(k))
                ++covered, drop.push_back(it.getCoord());
        }
        for (const auto& ijk : drop) {
            level.density->tree().setValueOff(ijk, 0.f);
            level.color->tree().setValueOff(ijk, openvdb::Vec3s(0.f));
        }
        if (outside)
            warnings.push_back("'" + reads[k].path + "': " + std::to_string(outside) +
                               " voxel(s) outside the level's region were ignored (only the "
                               "coarsest level may grow)");
        if (covered)
            warnings.push_back(
                "'" + reads[k].path + "': " + std::to_string(covered) +
                " voxel(s) lie where a finer level defines the medium and were ignored; "
                "edit that level's file instead");
    }
    fillCoveredFromFiner(volume);
    for (auto& level : volume.levels) {
        openvdb::tools::pruneInactive(level.density->tree());
        openvdb::tools::pruneInactive(level.color->tree());
    }
    volume.normaliseLevels();
    if (manifest.contains("layout") && manifest["layout"].is_object()) {
        try {
            const VolumeLayout layout = VolumeLayout::fromJson(manifest["layout"].dump(), dirText);
            // Keep the layout only if the levels still match it.
            bool same = layout.levels == int(volume.levels.size());
            for (int k = 0; same && k < layout.levels; ++k)
                same = *layout.transform(k) == volume.levels[k].transform() &&
                       volume.levels[k].domain ==
                           openvdb::CoordBBox(openvdb::Coord(0),
                                              openvdb::Coord(layout.resolution - 1));
            if (same) volume.layout = layout;
        } catch (const Error&) {
            warnings.push_back("'" + dirText + "': the manifest's layout is unreadable; ignored");
        }
    }
    if (manifest.contains("ref_camera") && manifest["ref_camera"].is_object())
        volume.refCamera = cameraFromJson(manifest["ref_camera"].dump(), dirText + ": ref_camera");
    if (manifest.contains("shell_centre")) {
        const nlohmann::json& c = manifest["shell_centre"];
        const auto finite = [](const nlohmann::json& v) {
            return v.is_number() && std::isfinite(v.get<double>());
        };
        if (c.is_array() && c.size() == 3 && finite(c[0]) && finite(c[1]) && finite(c[2]))
            volume.shellCentre = Vec3d(c[0].get<double>(), c[1].get<double>(), c[2].get<double>());
        else
            warnings.push_back("'" + dirText +
                               "': the manifest's shell_centre is not three finite numbers; "
                               "ignored");
    }
    if (manifest.contains("mpi")) {
        const fs::path path = fileInExport(manifest["mpi"], dir, "the \"mpi\"");
        report.mpi = readMpi(path.string(), exportId, manifestPath);
        report.mpiFile = path.string();
    }
    volume.validate();
    if (reportOut) *reportOut = std::move(report);
    return volume;
}

}  // namespace lh
