// Edits made to an export are honoured on import (houdini_export/dcc_edits.h, dcc_import.h):
// an edited colour grid wins over the untouched emission, an edited emission wins as before,
// both edited and disagreeing gives one warning, a manifest without checksums keeps the old
// rule and says so, a manifest that is malformed or belongs to other files is one error, and
// an exported MPI comes back. Edits are made the way python3-openvdb or a DCC makes them: the
// level file is read, changed and written back whole, with its metadata.
#include "houdini_export/dcc_edits.h"
#include "houdini_export/dcc_export.h"
#include "houdini_export/dcc_import.h"
#include "houdini_export/grid_checksum.h"

#include "core/errors.h"
#include "vdb/example_volume.h"

#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <functional>

namespace fs = std::filesystem;

namespace lh {
namespace {

fs::path freshDir(const std::string& name) {
    const fs::path p =
        fs::temp_directory_path() / ("lh_dcc_edits_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(p);
    return p;
}

using Grids = std::map<std::string, openvdb::GridBase::Ptr>;

// Reads a level file, lets `edit` change its grids, and writes it back whole.
void editFile(const fs::path& path, const std::function<void(Grids&)>& edit) {
    openvdb::initialize();
    openvdb::io::File in(path.string());
    in.open();
    openvdb::GridPtrVec grids = *in.getGrids();
    openvdb::MetaMap::Ptr meta = in.getMetadata();
    in.close();
    Grids byName;
    for (const auto& g : grids) byName[g->getName()] = g;
    edit(byName);
    openvdb::io::File(path.string()).write(grids, *meta);
}

template <typename GridT>
typename GridT::Ptr as(Grids& g, const std::string& name) {
    auto typed = openvdb::gridPtrCast<GridT>(g.at(name));
    EXPECT_TRUE(typed) << name;
    return typed;
}

nlohmann::json readJson(const fs::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

void writeJson(const fs::path& path, const nlohmann::json& j) { std::ofstream(path) << j.dump(2); }

// A level-0 shell voxel with density: import keeps it at the same index (only covered voxels
// are refilled from finer levels).
struct Probe {
    openvdb::Coord ijk;
    float sigma;
};

Probe firstVoxel(const fs::path& levelFile) {
    openvdb::initialize();
    openvdb::io::File in(levelFile.string());
    in.open();
    auto d = openvdb::gridPtrCast<openvdb::FloatGrid>(in.readGrid(kDccDensityGrid));
    in.close();
    for (auto it = d->cbeginValueOn(); it; ++it)
        if (*it > 0.5f) return {it.getCoord(), *it};
    ADD_FAILURE() << "no voxel with density in " << levelFile;
    return {};
}

void setColour(Grids& g, const DccConvention& conv, const openvdb::Coord& ijk,
               const openvdb::Vec3s& rgb) {
    as<openvdb::Vec3SGrid>(g, conv.colorGrid)->tree().setValueOn(ijk, rgb);
}

void setEmission(Grids& g, const DccConvention& conv, const openvdb::Coord& ijk,
                 const openvdb::Vec3s& e) {
    if (conv.splitEmission) {
        for (int c = 0; c < 3; ++c)
            as<openvdb::FloatGrid>(g, kDccEmissionChannelGrids[c])->tree().setValueOn(ijk, e[c]);
    } else {
        as<openvdb::Vec3SGrid>(g, kDccEmissionGrid)->tree().setValueOn(ijk, e);
    }
}

struct Exported {
    fs::path dir;
    Probe voxel;
    openvdb::Vec3s original;  // its colour before any edit
};

Exported exportExample(Dcc dcc, const std::string& tag, const Mpi* mpi = nullptr) {
    static const LightingVolume volume = makeExampleVolume(3, 16);
    Exported e;
    e.dir = freshDir(tag + "_" + dccConvention(dcc).name);
    exportForDcc(volume, e.dir.string(), {dcc}, mpi);
    e.voxel = firstVoxel(e.dir / dccLevelFileName(0));
    e.original = volume.levels[0].color->tree().getValue(e.voxel.ijk);
    return e;
}

bool contains(const std::vector<std::string>& lines, const std::string& what) {
    for (const auto& l : lines)
        if (l.find(what) != std::string::npos) return true;
    return false;
}

TEST(GridChecksum, SeesValueEditsButNotHowTheFileWasSaved) {
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(0.f);
    for (int i = 0; i < 20; ++i) grid->tree().setValueOn(openvdb::Coord(i, 2 * i, -i), 1.f + i);
    grid->tree().setValueOn(openvdb::Coord(100), 0.f);  // active but zero: as good as inactive
    const std::string before = gridChecksum(*grid);
    EXPECT_EQ(before.size(), 16u);
    // Saved again by another program: other metadata, no compression, the zero voxel dropped.
    const fs::path path = freshDir("checksum_resave");
    fs::create_directories(path);
    auto copy = grid->deepCopy();
    copy->setName("density");
    copy->insertMeta("written_by", openvdb::StringMetadata("some DCC"));
    copy->tree().setValueOff(openvdb::Coord(100), 0.f);
    openvdb::io::File out((path / "a.vdb").string());
    out.setCompression(openvdb::io::COMPRESS_NONE);
    out.write({copy});
    openvdb::io::File in((path / "a.vdb").string());
    in.open();
    EXPECT_EQ(gridChecksum(*in.readGrid("density")), before);
    in.close();
    // A tile counts as its voxels: a filled 8^3 block hashes alike as voxels and as one tile.
    auto voxels = openvdb::FloatGrid::create(0.f), tile = openvdb::FloatGrid::create(0.f);
    for (auto ijk = openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(7)).beginXYZ(); ijk; ++ijk)
        voxels->tree().setValueOn(*ijk, 2.f);
    tile->tree().addTile(1, openvdb::Coord(0), 2.f, true);
    EXPECT_EQ(gridChecksum(*voxels), gridChecksum(*tile));
    // One value changed, or one voxel moved: another checksum.
    grid->tree().setValueOn(openvdb::Coord(3, 6, -3), 4.5f);
    EXPECT_NE(gridChecksum(*grid), before);
    auto moved = openvdb::FloatGrid::create(0.f);
    moved->tree().setValueOn(openvdb::Coord(1, 0, 0), 1.f);
    auto unmoved = openvdb::FloatGrid::create(0.f);
    unmoved->tree().setValueOn(openvdb::Coord(0, 1, 0), 1.f);
    EXPECT_NE(gridChecksum(*moved), gridChecksum(*unmoved));
    fs::remove_all(path);
}

TEST(DccEdits, AnEditedColourGridWinsOverTheUntouchedEmission) {
    for (Dcc dcc : {Dcc::Houdini, Dcc::Blender}) {
        const DccConvention conv = dccConvention(dcc);
        const Exported e = exportExample(dcc, "colour");
        const openvdb::Vec3s edited(0.25f, 0.5f, 2.f);
        ASSERT_NE(e.original, edited);
        editFile(e.dir / dccLevelFileName(0),
                 [&](Grids& g) { setColour(g, conv, e.voxel.ijk, edited); });
        DccImportReport report;
        const LightingVolume back = importFromDcc(e.dir.string(), dcc, &report);
        EXPECT_EQ(back.levels[0].color->tree().getValue(e.voxel.ijk), edited) << conv.name;
        EXPECT_EQ(back.levels[0].density->tree().getValue(e.voxel.ijk), e.voxel.sigma) << conv.name;
        EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
        EXPECT_TRUE(contains(report.notes, "(level 0): '" + conv.colorGrid + "' was edited"))
            << conv.name;
        fs::remove_all(e.dir);
    }
}

TEST(DccEdits, AnEditedEmissionGridWinsAsBefore) {
    for (Dcc dcc : {Dcc::Houdini, Dcc::Blender}) {
        const DccConvention conv = dccConvention(dcc);
        const Exported e = exportExample(dcc, "emission");
        const openvdb::Vec3s radiance(3.f, 0.f, 0.5f);
        editFile(e.dir / dccLevelFileName(0),
                 [&](Grids& g) { setEmission(g, conv, e.voxel.ijk, radiance * e.voxel.sigma); });
        DccImportReport report;
        const LightingVolume back = importFromDcc(e.dir.string(), dcc, &report);
        const openvdb::Vec3s got = back.levels[0].color->tree().getValue(e.voxel.ijk);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], radiance[c], 1e-6 * 3) << conv.name;
        EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
        EXPECT_TRUE(report.notes.empty()) << report.notes.front();
        fs::remove_all(e.dir);
    }
}

TEST(DccEdits, BothEditedAndDisagreeingGivesOneWarningAndEmissionWins) {
    for (Dcc dcc : {Dcc::Houdini, Dcc::Blender}) {
        const DccConvention conv = dccConvention(dcc);
        const Exported e = exportExample(dcc, "both");
        const openvdb::Vec3s fromEmission(3.f, 0.f, 0.f), fromColour(0.f, 0.f, 3.f);
        editFile(e.dir / dccLevelFileName(0), [&](Grids& g) {
            setEmission(g, conv, e.voxel.ijk, fromEmission * e.voxel.sigma);
            setColour(g, conv, e.voxel.ijk, fromColour);
        });
        DccImportReport report;
        const LightingVolume back = importFromDcc(e.dir.string(), dcc, &report);
        const openvdb::Vec3s got = back.levels[0].color->tree().getValue(e.voxel.ijk);
        EXPECT_NEAR(got[0], 3.f, 1e-5) << conv.name;
        EXPECT_EQ(got[2], 0.f) << conv.name;
        ASSERT_EQ(report.warnings.size(), 1u) << conv.name;
        const std::string& w = report.warnings[0];
        const std::string emissionName = conv.splitEmission ? "emission_r/g/b" : "emission";
        for (const std::string& part :
             {std::string("level_0.vdb' (level 0)"), "'" + conv.colorGrid + "'",
              "'" + emissionName + "'", std::string("disagree in 1 voxel(s)")})
            EXPECT_NE(w.find(part), std::string::npos) << "'" << part << "' not in: " << w;
        fs::remove_all(e.dir);
    }
}

// Painting density, emission and colour together, consistently (as the docs' example does),
// is one edit: no warning.
TEST(DccEdits, BothEditedAndAgreeingIsNotAConflict) {
    const DccConvention conv = dccConvention(Dcc::Blender);
    const Exported e = exportExample(Dcc::Blender, "agree");
    const openvdb::Vec3s rgb(0.f, 0.f, 8.f);
    editFile(e.dir / dccLevelFileName(0), [&](Grids& g) {
        as<openvdb::FloatGrid>(g, "density")->tree().setValueOn(e.voxel.ijk, 200.f);
        setEmission(g, conv, e.voxel.ijk, rgb * 200.f);
        setColour(g, conv, e.voxel.ijk, rgb);
    });
    DccImportReport report;
    const LightingVolume back = importFromDcc(e.dir.string(), Dcc::Blender, &report);
    EXPECT_EQ(back.levels[0].color->tree().getValue(e.voxel.ijk), rgb);
    EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
    fs::remove_all(e.dir);
}

// A program that re-saves every grid at half precision changes every value a little: both
// radiance grids count as edited, but they still agree, so that is no conflict.
TEST(DccEdits, ReSavingAtHalfPrecisionIsNotAConflict) {
    for (Dcc dcc : {Dcc::Houdini, Dcc::Blender}) {
        const Exported e = exportExample(dcc, "half");
        for (int k = 0; k < 3; ++k)
            editFile(e.dir / dccLevelFileName(k), [&](Grids& g) {
                for (auto& [name, grid] : g) grid->setSaveFloatAsHalf(true);
            });
        // The values did change: the colour grid no longer has its checksum.
        const auto checksums =
            readManifestChecksums(readJson(e.dir / kDccManifestName), "manifest");
        ASSERT_TRUE(checksums.has_value());
        openvdb::io::File in((e.dir / dccLevelFileName(0)).string());
        in.open();
        EXPECT_TRUE(gridEdited((*checksums)[0], *in.readGrid(dccConvention(dcc).colorGrid)));
        in.close();
        DccImportReport report;
        const LightingVolume back = importFromDcc(e.dir.string(), dcc, &report);
        EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
        const openvdb::Vec3s got = back.levels[0].color->tree().getValue(e.voxel.ijk);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], e.original[c], 2e-3 * (1 + e.original[c]));
        fs::remove_all(e.dir);
    }
}

// An export without checksums (written before they existed, or by hand): the emission rule, so
// a colour edit is ignored, and one warning that says so (once, not per level).
TEST(DccEdits, WithoutChecksumsEmissionWinsAndImportSaysSoOnce) {
    const DccConvention conv = dccConvention(Dcc::Houdini);
    const Exported e = exportExample(Dcc::Houdini, "old");
    nlohmann::json m = readJson(e.dir / kDccManifestName);
    m.erase("checksum");
    for (auto& level : m["levels"]) level.erase("checksums");
    writeJson(e.dir / kDccManifestName, m);
    editFile(e.dir / dccLevelFileName(0),
             [&](Grids& g) { setColour(g, conv, e.voxel.ijk, openvdb::Vec3s(9.f)); });
    DccImportReport report;
    const LightingVolume back = importFromDcc(e.dir.string(), Dcc::Houdini, &report);
    const openvdb::Vec3s got = back.levels[0].color->tree().getValue(e.voxel.ijk);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], e.original[c], 1e-5 * (1 + e.original[c]));
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("has no grid checksums"), std::string::npos)
        << report.warnings[0];
    EXPECT_NE(report.warnings[0].find("an edit to 'Cd' alone is ignored"), std::string::npos)
        << report.warnings[0];
    fs::remove_all(e.dir);
}

void expectImportError(const fs::path& dir, Dcc dcc, const std::string& part) {
    try {
        importFromDcc(dir.string(), dcc);
        ADD_FAILURE() << "import succeeded; expected an error with '" << part << "'";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
}

TEST(DccEdits, AMalformedOrMismatchedManifestIsOneError) {
    const Exported e = exportExample(Dcc::Houdini, "bad_manifest");
    const fs::path manifest = e.dir / kDccManifestName;
    const nlohmann::json good = readJson(manifest);
    nlohmann::json m = good;
    m["levels"][1]["checksums"]["density"] = "not hex";
    writeJson(manifest, m);
    expectImportError(e.dir, Dcc::Houdini,
                      "level 1's \"checksums\" is not an object of grid name -> 16 hex digits");
    m = good;
    m["levels"][2].erase("checksums");
    writeJson(manifest, m);
    expectImportError(e.dir, Dcc::Houdini, "only 2 of 3 levels have \"checksums\"");
    m = good;
    m["checksum"] = "md5";
    writeJson(manifest, m);
    expectImportError(e.dir, Dcc::Houdini,
                      "\"checksum\" is \"md5\", expected \"lighthouse-active-voxels-v1\"");
    m = good;
    m["mpi"] = {{"file", "../elsewhere.vdb"}};
    writeJson(manifest, m);
    expectImportError(e.dir, Dcc::Houdini, "must be a plain name inside the export directory");
    // A level file from another export of the same volume: its export id gives it away.
    writeJson(manifest, good);
    const Exported other = exportExample(Dcc::Houdini, "other");
    fs::copy_file(other.dir / dccLevelFileName(1), e.dir / dccLevelFileName(1),
                  fs::copy_options::overwrite_existing);
    expectImportError(e.dir, Dcc::Houdini, "level_1.vdb' belongs to another export than");
    fs::remove_all(e.dir);
    fs::remove_all(other.dir);
}

TEST(DccEdits, TheMpiGoesOutAndComesBack) {
    Mpi mpi = Mpi::create(exampleCameras().ref, 1.0, 7.0, 4);
    float* p = mpi.pixel(2, 17, 9);
    p[0] = 0.5f, p[1] = 0.25f, p[2] = 2.f, p[3] = 0.75f;
    for (Dcc dcc : {Dcc::Houdini, Dcc::Blender}) {
        const Exported e = exportExample(dcc, "mpi", &mpi);
        // In the export: the planes' grids by name, in the program's axes.
        openvdb::io::File file((e.dir / kDccMpiFileName).string());
        file.open();
        auto alpha = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("mpi_alpha_P02"));
        auto rgb = openvdb::gridPtrCast<openvdb::Vec3SGrid>(file.readGrid("mpi_rgb_P02"));
        file.close();
        ASSERT_TRUE(alpha && rgb);
        EXPECT_EQ(alpha->tree().getValue(openvdb::Coord(17, 9, 0)), 0.75f);
        const DccConvention conv = dccConvention(dcc);
        const Vec3d world = mpiPlaneTransform(mpi.camera, mpi.planeDepths[2])
                                ->indexToWorld(openvdb::Coord(17, 9, 0));
        const Vec3d inDcc =
            alpha->transform().indexToWorld(Vec3d(17, 9, 0) + Vec3d(-conv.indexShift));
        EXPECT_TRUE(inDcc.eq(conv.worldToDcc * world, 1e-9))
            << inDcc << " vs " << conv.worldToDcc * world;
        // Back: the same MPI.
        DccImportReport report;
        importFromDcc(e.dir.string(), dcc, &report);
        ASSERT_TRUE(report.mpi.has_value()) << conv.name;
        EXPECT_EQ(report.mpi->planeCount(), 4);
        EXPECT_EQ(report.mpi->planeDepths, mpi.planeDepths);
        EXPECT_EQ(report.mpi->planes, mpi.planes);
        EXPECT_EQ(report.mpi->camera.fx, mpi.camera.fx);
        fs::remove_all(e.dir);
    }
}

// A shell's centre (the point predict collapsed its medium around) goes out in the manifest and
// comes back; a manifest whose centre is not three finite numbers loses it with one warning.
TEST(DccEdits, AShellsCentreGoesOutAndComesBack) {
    LightingVolume shell = makeExampleVolume(3, 16);
    shell.shellCentre = Vec3d(0.25, -0.5, 1.75);
    const fs::path dir = freshDir("shell_centre");
    exportForDcc(shell, dir.string(), {Dcc::Blender});
    DccImportReport report;
    const LightingVolume back = importFromDcc(dir.string(), Dcc::Blender, &report);
    EXPECT_TRUE(report.warnings.empty());
    ASSERT_TRUE(back.shellCentre.has_value());
    EXPECT_EQ(*back.shellCentre, *shell.shellCentre);

    nlohmann::json m = readJson(dir / kDccManifestName);
    m["shell_centre"] = {0.25, "up", 1.75};
    writeJson(dir / kDccManifestName, m);
    const LightingVolume damaged = importFromDcc(dir.string(), Dcc::Blender, &report);
    EXPECT_FALSE(damaged.shellCentre.has_value());
    EXPECT_TRUE(contains(report.warnings, "shell_centre is not three finite numbers"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace lh
