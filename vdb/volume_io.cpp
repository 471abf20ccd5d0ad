#include "vdb/volume_io.h"

#include "core/atomic_file.h"
#include "core/errors.h"
#include "vdb/grid_selection.h"
#include "vdb/mantissa_rounding.h"
#include "vdb/safe_read.h"

#include <openvdb/io/File.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>

namespace lh {

namespace {

void initialiseOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

struct VdbContents {
    openvdb::GridPtrVec grids;
    openvdb::MetaMap::Ptr meta;
};

VdbContents readVdb(const std::string& path, GridSelection which) {
    initialiseOpenVdb();
    if (!std::filesystem::exists(path)) throw FileError("'" + path + "' does not exist");
    if (std::filesystem::is_directory(path))
        throw FileError("'" + path + "' is a directory, not a .vdb file");
    // A FIFO or a device would block the read (and its trial read) for ever.
    if (!std::filesystem::is_regular_file(path))
        throw FileError("'" + path + "' is not a regular file");
    probeVdbReadable(path, 0, 0, which);
    try {
        openvdb::io::File file(path);
        file.open(/*delayLoad=*/false);
        VdbContents contents{readSelectedGrids(file, which), file.getMetadata()};
        file.close();
        return contents;
    } catch (const openvdb::Exception& e) {
        throw FileError("'" + path + "' is not a readable VDB file (" + e.what() + ")");
    } catch (const std::exception& e) {
        throw FileError("'" + path + "' could not be read as a VDB file (" + e.what() + ")");
    }
}

struct Counts {
    std::size_t nan = 0, posInf = 0, negative = 0;
    std::size_t total() const { return nan + posInf + negative; }
};

float fixDensity(float v, Counts& c) {
    if (std::isnan(v)) return ++c.nan, 0.f;
    if (v == std::numeric_limits<float>::infinity()) return ++c.posInf, kOpaqueDensity;
    if (v < 0.f) return ++c.negative, 0.f;
    return v;
}

float fixRadiance(float v, Counts& c) {
    if (std::isnan(v)) return ++c.nan, 0.f;
    if (v == std::numeric_limits<float>::infinity()) return ++c.posInf, kMaxRadiance;
    if (v < 0.f) return ++c.negative, 0.f;
    return v;
}

// Applies the non-finite policy to every stored value (voxels, tiles, background).
template <typename GridT, typename FixFn>
void sanitiseGrid(GridT& grid, FixFn fix, const std::string& path, NonFinitePolicy policy,
                  std::vector<std::string>* warnings) {
    Counts counts;
    for (auto it = grid.tree().beginValueAll(); it; ++it) {
        const auto v = it.getValue();
        const auto fixed = fix(v, counts);
        if (policy == NonFinitePolicy::Sanitise && !(fixed == v)) it.setValue(fixed);
    }
    const auto bg = grid.background();
    Counts bgCounts;
    const auto fixedBg = fix(bg, bgCounts);
    if (bgCounts.total() && policy == NonFinitePolicy::Sanitise)
        grid.tree().root().setBackground(fixedBg, /*updateChildNodes=*/true);
    if (!counts.total() && !bgCounts.total()) return;
    const std::string what = std::to_string(counts.nan) + " NaN, " + std::to_string(counts.posInf) +
                             " +Inf, " + std::to_string(counts.negative) + " negative value(s)" +
                             (bgCounts.total() ? " and an invalid background" : "");
    if (policy == NonFinitePolicy::Reject)
        throw FileError("'" + path + "': grid '" + grid.getName() + "' holds " + what);
    if (warnings)
        warnings->push_back("'" + path + "': grid '" + grid.getName() + "': replaced " + what +
                            " (NaN -> 0, +Inf -> opaque/max, negative -> 0)");
}

float fixColorComponent(float v, Counts& c) { return fixRadiance(v, c); }

openvdb::Vec3s fixColor(const openvdb::Vec3s& v, Counts& c) {
    return openvdb::Vec3s(fixColorComponent(v.x(), c), fixColorComponent(v.y(), c),
                          fixColorComponent(v.z(), c));
}

// "density_L2" -> "_L2"; "density" -> "". Returns false if not a density name.
bool densitySuffix(const std::string& name, std::string& suffix) {
    if (name.rfind("density", 0) != 0) return false;
    suffix = name.substr(7);
    return true;
}

openvdb::CoordBBox storedDomain(const openvdb::GridBase& grid) {
    auto lo = grid.getMetadata<openvdb::Vec3IMetadata>("lighthouse_domain_min");
    auto hi = grid.getMetadata<openvdb::Vec3IMetadata>("lighthouse_domain_max");
    if (lo && hi)
        return openvdb::CoordBBox(openvdb::Coord(lo->value()), openvdb::Coord(hi->value()));
    return openvdb::CoordBBox();  // empty: use the active bounding box
}

}  // namespace

namespace {

// A stored value's largest component, and the value clamped to kHalfSafeMax per component.
float largestComponent(float v) { return v; }
float largestComponent(const openvdb::Vec3s& v) { return std::max({v.x(), v.y(), v.z()}); }
float clampedToHalf(float v) { return std::min(v, kHalfSafeMax); }
openvdb::Vec3s clampedToHalf(const openvdb::Vec3s& v) {
    return openvdb::Vec3s(clampedToHalf(v.x()), clampedToHalf(v.y()), clampedToHalf(v.z()));
}

// Whether any value (voxel or tile) of the grid exceeds kHalfSafeMax: a read-only pass, so
// that only grids that need clamping are copied.
template <typename GridT>
bool exceedsHalf(const GridT& grid) {
    for (auto it = grid.cbeginValueAll(); it; ++it)
        if (largestComponent(*it) > kHalfSafeMax) return true;
    return false;
}

// Clamps every value (voxels and tiles) to kHalfSafeMax per component; returns how many changed.
template <typename GridT>
std::size_t clampToHalf(GridT& grid) {
    std::size_t n = 0;
    for (auto it = grid.beginValueAll(); it; ++it)
        if (largestComponent(*it) > kHalfSafeMax) it.setValue(clampedToHalf(*it)), ++n;
    return n;
}

// The grid as it is written: a shallow copy (metadata and names are set on it, the tree is
// shared), or a deep copy with its values rounded to `options.mantissaBits` and, with half
// precision and values beyond it, clamped to kHalfSafeMax (adding the count to `clamped`).
template <typename GridPtr>
GridPtr gridToSave(const GridPtr& grid, const VolumeSaveOptions& options, std::size_t& clamped) {
    const bool clamp = options.halfPrecision && exceedsHalf(*grid);
    if (!clamp && options.mantissaBits == 0) return grid->copy();
    GridPtr copy = grid->deepCopy();
    if (options.mantissaBits > 0) roundGridToMantissaBits(*copy, options.mantissaBits);
    if (clamp) clamped += clampToHalf(*copy);
    return copy;
}

// The MPI's grids, fresh copies made for saving, rounded in place: alpha planes are
// FloatGrids, colour planes Vec3SGrids.
void roundMpiGrid(openvdb::GridBase& grid, int bits) {
    if (auto* f = dynamic_cast<openvdb::FloatGrid*>(&grid))
        roundGridToMantissaBits(*f, bits);
    else if (auto* v = dynamic_cast<openvdb::Vec3SGrid*>(&grid))
        roundGridToMantissaBits(*v, bits);
}

}  // namespace

std::string halfClampWarning(const VolumeSaveReport& report) {
    if (report.valuesClampedToHalf == 0) return "";
    return std::to_string(report.valuesClampedToHalf) + " value(s) above " +
           std::to_string(int(kHalfSafeMax)) + " were clamped to fit half precision";
}

VolumeSaveReport saveVdb(const std::string& path, const LightingVolume* volume, const Mpi* mpi,
                         const VolumeSaveOptions& options) {
    VolumeSaveReport report;
    initialiseOpenVdb();
    if (!volume && !mpi) throw InputError("nothing to save to '" + path + "'");
    validateMantissaBits(options.mantissaBits, options.halfPrecision, "mantissa bits");
    openvdb::GridPtrVec grids;
    openvdb::MetaMap fileMeta;
    fileMeta.insertMeta("lighthouse_format_version", openvdb::Int32Metadata(kVolumeFormatVersion));
    if (volume) {
        volume->validate();
        if (volume->layout)
            fileMeta.insertMeta("lighthouse_layout",
                                openvdb::StringMetadata(volume->layout->toJson()));
        if (volume->refCamera)
            fileMeta.insertMeta("lighthouse_ref_camera",
                                openvdb::StringMetadata(cameraToJson(*volume->refCamera)));
        if (volume->shellCentre)
            fileMeta.insertMeta("lighthouse_shell_centre",
                                openvdb::Vec3DMetadata(*volume->shellCentre));
        for (std::size_t k = 0; k < volume->levels.size(); ++k) {
            const VolumeLevel& level = volume->levels[k];
            const auto density = gridToSave(level.density, options, report.valuesClampedToHalf);
            const auto color = gridToSave(level.color, options, report.valuesClampedToHalf);
            for (openvdb::GridBase::Ptr g :
                 {openvdb::GridBase::Ptr(density), openvdb::GridBase::Ptr(color)}) {
                g->setName(g == density ? densityGridName(int(k)) : colorGridName(int(k)));
                g->insertMeta("level", openvdb::Int32Metadata(int(k)));
                g->insertMeta("lighthouse_domain_min",
                              openvdb::Vec3IMetadata(level.domain.min().asVec3i()));
                g->insertMeta("lighthouse_domain_max",
                              openvdb::Vec3IMetadata(level.domain.max().asVec3i()));
                g->setSaveFloatAsHalf(options.halfPrecision);
                grids.push_back(g);
            }
        }
    }
    if (mpi) {
        if (!volume)
            fileMeta.insertMeta("lighthouse_ref_camera",
                                openvdb::StringMetadata(cameraToJson(mpi->camera)));
        fileMeta.insertMeta("lighthouse_mpi_camera",
                            openvdb::StringMetadata(cameraToJson(mpi->camera)));
        for (auto& g : mpiToGrids(*mpi)) {
            if (options.mantissaBits > 0) roundMpiGrid(*g, options.mantissaBits);
            g->setSaveFloatAsHalf(options.halfPrecision);
            grids.push_back(g);
        }
    }
    AtomicOutput out(path);
    try {
        openvdb::io::File file(out.tempPath());
        file.setCompression(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
        file.write(grids, fileMeta);
        file.close();
    } catch (const openvdb::Exception& e) {
        throw FileError("cannot write '" + path + "': " + e.what());
    }
    out.commit();
    return report;
}

namespace {

LightingVolume volumeFromContents(const VdbContents& contents, const std::string& path,
                                  std::vector<std::string>* warnings,
                                  const VolumeLoadOptions& options) {
    std::map<std::string, openvdb::GridBase::Ptr> byName;
    for (const auto& g : contents.grids) byName[g->getName()] = g;

    LightingVolume volume;
    std::vector<std::string> emptyDensity;  // density grids with neither voxels nor a domain
    for (const auto& [name, grid] : byName) {
        std::string suffix;
        if (!densitySuffix(name, suffix)) continue;
        auto density = openvdb::gridPtrCast<openvdb::FloatGrid>(grid);
        if (!density)
            throw FileError("'" + path + "': grid '" + name + "' is " + gridKind(*grid) +
                            ", expected a FloatGrid (extinction density)");
        openvdb::GridBase::Ptr colorBase;
        for (const char* stem : {"color", "Cd", "colour"})
            if (byName.count(stem + suffix)) colorBase = byName[stem + suffix];
        if (!colorBase)
            throw FileError("'" + path + "': density grid '" + name +
                            "' has no matching Vec3SGrid 'color" + suffix + "'");
        auto color = openvdb::gridPtrCast<openvdb::Vec3SGrid>(colorBase);
        if (!color)
            throw FileError("'" + path + "': grid '" + colorBase->getName() + "' is " +
                            gridKind(*colorBase) + ", expected a Vec3SGrid (linear RGB radiance)");
        for (const openvdb::GridBase* g :
             {(const openvdb::GridBase*)density.get(), (const openvdb::GridBase*)color.get()})
            if (!g->transform().isLinear())
                throw FileError("'" + path + "': grid '" + g->getName() +
                                "' has a non-affine (frustum) transform; resample it onto a "
                                "linear transform first");
        if (density->transform() != color->transform())
            throw FileError("'" + path + "': grids '" + name + "' and '" + color->getName() +
                            "' have different transforms");
        sanitiseGrid(*density, fixDensity, path, options.nonFinite, warnings);
        sanitiseGrid(*color, fixColor, path, options.nonFinite, warnings);

        VolumeLevel level;
        level.density = density;
        level.color = color;
        level.domain = storedDomain(*density);
        if (level.domain.empty()) level.domain = density->evalActiveVoxelBoundingBox();
        if (level.domain.empty()) {
            emptyDensity.push_back(name);
            if (warnings)
                warnings->push_back("'" + path + "': grid '" + name + "' is empty; ignored");
            continue;
        }
        volume.levels.push_back(level);
    }
    if (volume.levels.empty() && !emptyDensity.empty())
        throw FileError(
            "'" + path + "': density grid '" + emptyDensity.front() +
            "' is empty (no active voxels, and no stored domain to give the level its extent), "
            "so the file holds no volume to render");
    if (volume.levels.empty()) {
        bool anyColor = false;
        for (const auto& [name, grid] : byName) anyColor |= name.rfind("color", 0) == 0;
        throw FileError(
            "'" + path + "': " +
            (anyColor ? std::string("has a color grid but no FloatGrid 'density'")
                      : std::string("holds no lighting volume (no 'density' + 'color' grids)")));
    }
    try {
        volume.normaliseLevels();
    } catch (const InputError& e) {
        throw FileError("'" + path + "': " + e.what());
    }
    const auto& meta = *contents.meta;
    if (auto layout = meta.getMetadata<openvdb::StringMetadata>("lighthouse_layout"))
        volume.layout = VolumeLayout::fromJson(layout->value(), path);
    if (auto cam = meta.getMetadata<openvdb::StringMetadata>("lighthouse_ref_camera"))
        volume.refCamera = cameraFromJson(cam->value(), path + ": lighthouse_ref_camera");
    if (auto centre = meta.getMetadata<openvdb::Vec3DMetadata>("lighthouse_shell_centre")) {
        if (!centre->value().isFinite())
            throw FileError("'" + path +
                            "': lighthouse_shell_centre is not a finite point; the file is "
                            "damaged, write it again with lighthouse predict or shell");
        volume.shellCentre = centre->value();
    }
    return volume;
}

// The MPI of a file, or nullopt when it holds none (no 'lighthouse_mpi_camera' metadata).
std::optional<Mpi> mpiFromContents(const VdbContents& contents, const std::string& path) {
    auto cam = contents.meta->getMetadata<openvdb::StringMetadata>("lighthouse_mpi_camera");
    if (!cam) return std::nullopt;
    return mpiFromGrids(contents.grids, cameraFromJson(cam->value(), path), path);
}

}  // namespace

LightingVolume loadVolume(const std::string& path, std::vector<std::string>* warnings,
                          const VolumeLoadOptions& options) {
    return volumeFromContents(readVdb(path, GridSelection::LightingVolume), path, warnings,
                              options);
}

VolumeFile loadVolumeFile(const std::string& path, std::vector<std::string>* warnings,
                          const VolumeLoadOptions& options) {
    const VdbContents contents = readVdb(path, GridSelection::Every);
    return {volumeFromContents(contents, path, warnings, options), mpiFromContents(contents, path)};
}

Mpi loadMpi(const std::string& path) {
    std::optional<Mpi> mpi = mpiFromContents(readVdb(path, GridSelection::Every), path);
    if (!mpi) throw FileError("'" + path + "': holds no MPI (no 'lighthouse_mpi_camera' metadata)");
    return *mpi;
}

}  // namespace lh
