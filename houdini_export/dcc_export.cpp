#include "houdini_export/dcc_export.h"

#include "core/atomic_file.h"
#include "core/errors.h"
#include "houdini_export/grid_checksum.h"
#include "houdini_export/shells.h"

#include <openvdb/io/File.h>
#include <nlohmann/json.hpp>

#include <fcntl.h>  // AT_FDCWD
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>  // renameat2 (glibc; g++ defines _GNU_SOURCE)
#include <filesystem>
#include <fstream>
#include <random>
#include <system_error>

namespace fs = std::filesystem;

namespace lh {

void clampForDcc(float& sigma, openvdb::Vec3s& color, float maxValue, bool& sigmaChanged,
                 bool& colorChanged) {
    sigmaChanged = colorChanged = false;
    for (int c = 0; c < 3; ++c) {
        float v = color[c];
        if (!(v >= 0.f)) v = 0.f;  // NaN or negative: not a radiance
        if (v > maxValue) v = maxValue;
        if (v != color[c]) colorChanged = true, color[c] = v;
    }
    float s = sigma;
    if (!(s >= 0.f)) s = 0.f;
    const float peak = std::max({1.f, color[0], color[1], color[2]});
    const float sigmaMax = maxValue / peak;
    if (s > sigmaMax) s = sigmaMax;
    if (s != sigma) sigmaChanged = true, sigma = s;
}

namespace {

openvdb::Mat4d rotationAsMat4(const Mat3d& r) {
    // OpenVDB multiplies row vectors from the left (v' = v M), so a column-vector rotation R
    // enters as its transpose.
    openvdb::Mat4d m = openvdb::Mat4d::identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[i][j] = r[j][i];
    return m;
}

struct LevelGrids {
    openvdb::FloatGrid::Ptr density;
    openvdb::FloatGrid::Ptr emissionChannel[3];  // Blender
    openvdb::Vec3SGrid::Ptr emission, color;     // emission: Houdini
    openvdb::GridCPtrVec all() const {
        openvdb::GridCPtrVec v{density};
        if (emission) v.push_back(emission);
        for (const auto& g : emissionChannel)
            if (g) v.push_back(g);
        v.push_back(color);
        return v;
    }
};

// A lighthouse transform in the program's axes (and, for Blender, its cell convention).
openvdb::math::Transform::Ptr toDccTransform(const openvdb::math::Transform& xf,
                                             const DccConvention& conv) {
    auto out = xf.copy();
    if (conv.indexShift != 0.0) out->preTranslate(Vec3d(conv.indexShift));
    out->postMult(rotationAsMat4(conv.worldToDcc));
    return out;
}

LevelGrids convertShell(const VolumeLevel& shell, int k, const DccConvention& conv,
                        const DccExportOptions& options, DccClampReport& clamp) {
    LevelGrids g;
    g.density = openvdb::FloatGrid::create(0.f);
    if (conv.splitEmission)
        for (auto& ch : g.emissionChannel) ch = openvdb::FloatGrid::create(0.f);
    else
        g.emission = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    g.color = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    const auto xf = toDccTransform(shell.transform(), conv);
    const double voxel = std::cbrt(shell.voxelVolume());  // metres
    auto d = g.density->getAccessor();
    auto c = g.color->getAccessor();
    auto srcColor = shell.color->getConstAccessor();
    for (auto it = shell.density->cbeginValueOn(); it; ++it) {
        float sigma = *it;
        openvdb::Vec3s rgb = srcColor.getValue(it.getCoord());
        const float before = sigma;
        bool sigmaChanged, colorChanged;
        clampForDcc(sigma, rgb, options.maxValue, sigmaChanged, colorChanged);
        if (sigmaChanged && before > 0 && std::isfinite(before)) {
            ++clamp.densityClamped;
            if (double(sigma) * voxel < 10.0 && double(before) * voxel >= 10.0)
                ++clamp.nowTranslucent;
        } else if (sigmaChanged) {
            ++clamp.densityClamped;
        }
        if (colorChanged) ++clamp.radianceClamped;
        if (!(sigma > 0.f)) continue;  // empty space stays inactive
        d.setValueOn(it.getCoord(), sigma);
        if (g.emission) g.emission->tree().setValueOn(it.getCoord(), rgb * sigma);
        for (int ch = 0; ch < 3; ++ch)
            if (g.emissionChannel[ch])
                g.emissionChannel[ch]->tree().setValueOn(it.getCoord(), rgb[ch] * sigma);
        c.setValueOn(it.getCoord(), rgb);
    }
    const openvdb::Vec3i lo = shell.domain.min().asVec3i(), hi = shell.domain.max().asVec3i();
    for (const auto& constGrid : g.all()) {
        auto grid = openvdb::ConstPtrCast<openvdb::GridBase>(constGrid);
        grid->setTransform(xf->copy());
        grid->insertMeta("level", openvdb::Int32Metadata(k));
        // The level's region in its own index space (unchanged by the axis rotation).
        grid->insertMeta("lighthouse_domain_min", openvdb::Vec3IMetadata(lo));
        grid->insertMeta("lighthouse_domain_max", openvdb::Vec3IMetadata(hi));
    }
    g.density->setName(kDccDensityGrid);
    g.density->setGridClass(openvdb::GRID_FOG_VOLUME);
    if (g.emission) {
        g.emission->setName(kDccEmissionGrid);
        g.emission->setVectorType(
            openvdb::VEC_INVARIANT);  // Houdini: "Tuple/Color", not a direction
    }
    for (int ch = 0; ch < 3; ++ch)
        if (g.emissionChannel[ch]) g.emissionChannel[ch]->setName(kDccEmissionChannelGrids[ch]);
    g.color->setName(conv.colorGrid);
    g.color->setVectorType(openvdb::VEC_INVARIANT);
    return g;
}

// File metadata of every file of an export.
openvdb::MetaMap exportMetadata(const DccConvention& conv, const std::string& exportId) {
    openvdb::MetaMap meta;
    meta.insertMeta("lighthouse_export_for", openvdb::StringMetadata(conv.name));
    meta.insertMeta("lighthouse_export_version", openvdb::Int32Metadata(kDccExportVersion));
    meta.insertMeta("lighthouse_export_id", openvdb::StringMetadata(exportId));
    meta.insertMeta("lighthouse_axes", openvdb::StringMetadata(conv.axesText));
    return meta;
}

void writeVdbFile(const std::string& path, const openvdb::GridCPtrVec& grids,
                  const openvdb::MetaMap& meta) {
    try {
        openvdb::io::File file(path);
        file.setCompression(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
        file.write(grids, meta);
        file.close();
    } catch (const openvdb::Exception& e) {
        throw FileError("cannot write '" + path + "': " + e.what());
    }
}

void writeLevelFile(const std::string& path, const LevelGrids& g, int k, int levels,
                    const DccConvention& conv, const std::string& exportId) {
    openvdb::MetaMap meta = exportMetadata(conv, exportId);
    meta.insertMeta("lighthouse_export_level", openvdb::Int32Metadata(k));
    meta.insertMeta("lighthouse_export_levels", openvdb::Int32Metadata(levels));
    writeVdbFile(path, g.all(), meta);
}

// The MPI's planes as volume_io writes them (the camera in lighthouse's frame, which import
// reads back), their transforms in the program's axes so that the planes show where they are.
void writeMpiFile(const std::string& path, const Mpi& mpi, const DccConvention& conv,
                  const std::string& exportId) {
    openvdb::MetaMap meta = exportMetadata(conv, exportId);
    meta.insertMeta("lighthouse_mpi_camera", openvdb::StringMetadata(cameraToJson(mpi.camera)));
    openvdb::GridCPtrVec grids;
    for (const auto& grid : mpiToGrids(mpi)) {
        grid->setTransform(toDccTransform(grid->transform(), conv));
        grids.push_back(grid);
    }
    writeVdbFile(path, grids, meta);
}

// 16 random hex digits naming one export: the manifest and every file carry it, so that a
// manifest is never matched with another export's files.
std::string newExportId() {
    std::random_device rd;
    char text[17];
    std::snprintf(text, sizeof text, "%08x%08x", unsigned(rd()), unsigned(rd()));
    return text;
}

bool isExportDirectory(const fs::path& dir) {
    return fs::is_directory(dir) && fs::is_regular_file(dir / kDccManifestName);
}

// A fresh, unused directory name beside `finalDir` (core/temporary_files.h), so that the next
// export removes it if this process is killed before it is renamed or removed.
fs::path temporaryDirectoryBeside(const fs::path& finalDir, const char* kind) {
    for (int attempt = 0; attempt < 100; ++attempt) {
        const fs::path p = temporaryBeside(finalDir.string(), kind, /*keepExtension=*/false);
        if (!fs::exists(p)) return p;
    }
    throw FileError("cannot find a free temporary name beside '" + finalDir.string() + "'");
}

// Puts the complete export `fresh` in place of the export `finalDir`, then removes the old
// one. Where the file system swaps two names in one step (renameat2's RENAME_EXCHANGE: ext4,
// xfs, btrfs, tmpfs), a kill at any moment leaves a whole export under the final name, the old
// or the new. Elsewhere the old export is first renamed aside, so that a kill between the two
// renames leaves no export under the final name (both stay whole, under temporary names).
void replaceExport(const fs::path& fresh, const fs::path& finalDir) {
    if (::renameat2(AT_FDCWD, fresh.c_str(), AT_FDCWD, finalDir.c_str(), RENAME_EXCHANGE) == 0) {
        std::error_code ignored;
        fs::remove_all(fresh, ignored);  // it now holds the old export
        return;
    }
    if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP)
        throw fs::filesystem_error("cannot swap in the new export", fresh, finalDir,
                                   std::error_code(errno, std::generic_category()));
    const fs::path old = temporaryDirectoryBeside(finalDir, "old");
    fs::rename(finalDir, old);
    fs::rename(fresh, finalDir);
    std::error_code ignored;
    fs::remove_all(old, ignored);
}

}  // namespace

DccExportReport exportForDcc(const LightingVolume& volume, const std::string& outDir,
                             const DccExportOptions& options, const Mpi* mpi) {
    volume.validate();
    if (mpi) mpi->validate();
    if (!(options.maxValue > 0) || !std::isfinite(options.maxValue))
        throw InputError("export value limit must be finite and positive");
    const DccConvention conv = dccConvention(options.dcc);
    fs::path finalDir = fs::path(outDir);
    if (finalDir.filename().empty()) finalDir = finalDir.parent_path();  // "out/" -> "out"
    const fs::path parent = finalDir.parent_path().empty() ? fs::path(".") : finalDir.parent_path();
    if (!fs::is_directory(parent))
        throw FileError("cannot write '" + outDir + "': directory '" + parent.string() +
                        "' does not exist");
    if (fs::exists(finalDir) && !isExportDirectory(finalDir))
        throw FileError("'" + outDir + "' exists and is not a lighthouse export (no " +
                        kDccManifestName + "); refusing to overwrite it");
    if (fs::exists(finalDir) && !options.replaceExisting)
        throw FileError(
            "'" + outDir +
            "' is an existing export, and edits made to it in Blender or Houdini would be "
            "lost; pass --force to replace it, or choose another directory");

    DccExportReport report;
    const std::vector<VolumeLevel> shells = makeShells(volume);
    removeAbandonedTemporaries(parent.string());  // of exports killed before they were renamed
    const fs::path tmp = temporaryDirectoryBeside(parent / finalDir.filename(), "tmp");
    nlohmann::json manifest;
    const std::string exportId = newExportId();
    try {
        fs::create_directory(tmp);
        manifest["lighthouse_export"] = kDccExportVersion;
        manifest["export_id"] = exportId;
        manifest["for"] = conv.name;
        manifest["axes"] = conv.axesText;
        nlohmann::json rot = nlohmann::json::array();
        for (int i = 0; i < 3; ++i)
            rot.push_back({conv.worldToDcc[i][0], conv.worldToDcc[i][1], conv.worldToDcc[i][2]});
        manifest["world_to_dcc"] = rot;
        manifest["index_shift"] = conv.indexShift;
        manifest["units"] = "scene units (metres); density per unit length";
        manifest["grids"] = {
            {"density", kDccDensityGrid},
            {"emission", conv.splitEmission ? nlohmann::json(kDccEmissionChannelGrids)
                                            : nlohmann::json(kDccEmissionGrid)},
            {"color", conv.colorGrid}};
        manifest["max_value"] = options.maxValue;
        if (volume.layout) manifest["layout"] = nlohmann::json::parse(volume.layout->toJson());
        if (volume.refCamera)
            manifest["ref_camera"] = nlohmann::json::parse(cameraToJson(*volume.refCamera));
        if (volume.shellCentre)
            manifest["shell_centre"] = {volume.shellCentre->x(), volume.shellCentre->y(),
                                        volume.shellCentre->z()};
        nlohmann::json levels = nlohmann::json::array();
        for (std::size_t k = 0; k < shells.size(); ++k) {
            const LevelGrids g = convertShell(shells[k], int(k), conv, options, report.clamp);
            const std::string name = dccLevelFileName(int(k));
            writeLevelFile((tmp / name).string(), g, int(k), int(shells.size()), conv, exportId);
            report.files.push_back((finalDir / name).string());
            report.activeVoxels.push_back(g.density->activeVoxelCount());
            nlohmann::json checksums = nlohmann::json::object();
            for (const auto& grid : g.all()) checksums[grid->getName()] = gridChecksum(*grid);
            levels.push_back({{"file", name},
                              {"voxel_size", std::cbrt(shells[k].voxelVolume())},
                              {"active_voxels", g.density->activeVoxelCount()},
                              {"checksums", checksums}});
        }
        manifest["levels"] = levels;
        manifest["checksum"] = kGridChecksumMethod;
        if (mpi) {
            writeMpiFile((tmp / kDccMpiFileName).string(), *mpi, conv, exportId);
            report.mpiFile = (finalDir / kDccMpiFileName).string();
            manifest["mpi"] = {{"file", kDccMpiFileName},
                               {"planes", mpi->planeCount()},
                               {"width", mpi->camera.width},
                               {"height", mpi->camera.height}};
        }
        manifest["clamped"] = {{"density_voxels", report.clamp.densityClamped},
                               {"radiance_voxels", report.clamp.radianceClamped},
                               {"now_translucent_voxels", report.clamp.nowTranslucent}};
        std::ofstream(tmp / kDccManifestName) << manifest.dump(2) << "\n";
        if (!fs::is_regular_file(tmp / kDccManifestName) ||
            fs::file_size(tmp / kDccManifestName) == 0)
            throw FileError("cannot write '" + (finalDir / kDccManifestName).string() + "'");
        if (fs::exists(finalDir))
            replaceExport(tmp, finalDir);
        else
            fs::rename(tmp, finalDir);
    } catch (const fs::filesystem_error& e) {
        std::error_code ignored;
        fs::remove_all(tmp, ignored);
        throw FileError("cannot write export '" + outDir + "': " + e.what());
    } catch (...) {
        std::error_code ignored;
        fs::remove_all(tmp, ignored);
        throw;
    }
    if (report.clamp.changedAnything()) {
        report.warnings.push_back(
            "values above " + std::to_string(int(options.maxValue)) +
            " (half-precision limit) were clamped: density in " +
            std::to_string(report.clamp.densityClamped) + " voxel(s), radiance in " +
            std::to_string(report.clamp.radianceClamped) + " voxel(s)" +
            (report.clamp.nowTranslucent
                 ? "; " + std::to_string(report.clamp.nowTranslucent) +
                       " opaque voxel(s) became translucent"
                 : std::string("; opaque voxels stay opaque, so surfaces keep their radiance")));
    }
    return report;
}

}  // namespace lh
