// Export and import: axes, grid names and types, the half-precision clamp, the directory
// written atomically, and a volume that comes back rendering as it went out.
#include "houdini_export/dcc_export.h"
#include "houdini_export/dcc_import.h"
#include "houdini_export/shells.h"

#include "core/errors.h"
#include "image/metrics.h"
#include "render/envmap.h"
#include "vdb/example_volume.h"
#include "vdb/volume_io.h"

#include <gtest/gtest.h>
#include <openvdb/io/File.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace lh {
namespace {

fs::path freshDir(const std::string& name) {
    const fs::path p =
        fs::temp_directory_path() / ("lh_dcc_test_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(p);
    return p;
}

openvdb::GridPtrVec readAll(const fs::path& path) {
    openvdb::initialize();
    openvdb::io::File file(path.string());
    file.open();
    auto grids = *file.getGrids();
    file.close();
    return grids;
}

openvdb::GridBase::Ptr byName(const openvdb::GridPtrVec& grids, const std::string& name) {
    for (const auto& g : grids)
        if (g->getName() == name) return g;
    return nullptr;
}

TEST(DccConvention, AxesAreRotationsThatPutUpAndForwardWhereEachProgramExpects) {
    for (Dcc dcc : {Dcc::Blender, Dcc::Houdini}) {
        const Mat3d r = dccConvention(dcc).worldToDcc;
        EXPECT_NEAR(r.det(), 1.0, 1e-12);  // a rotation: no mirror, no scale (metres stay metres)
        EXPECT_TRUE((r * r.transpose()).eq(Mat3d::identity(), 1e-12));
        EXPECT_TRUE((r * Vec3d(1, 0, 0)).eq(Vec3d(1, 0, 0)));  // right stays +X in both
    }
    const Mat3d b = dccConvention(Dcc::Blender).worldToDcc,
                h = dccConvention(Dcc::Houdini).worldToDcc;
    EXPECT_TRUE((b * Vec3d(0, -1, 0)).eq(Vec3d(0, 0, 1)));  // up (-y) is Blender +Z
    EXPECT_TRUE((b * Vec3d(0, 0, 1)).eq(Vec3d(0, 1, 0)));   // forward (+z) is Blender +Y
    EXPECT_TRUE((h * Vec3d(0, -1, 0)).eq(Vec3d(0, 1, 0)));  // up is Houdini +Y
    EXPECT_TRUE((h * Vec3d(0, 0, 1)).eq(Vec3d(0, 0, -1)));  // forward is Houdini -Z (camera view)
    EXPECT_EQ(parseDcc("Blender", "--for"), Dcc::Blender);
    EXPECT_THROW(parseDcc("maya", "--for"), InputError);
}

TEST(DccClamp, KeepsOpaqueEmittersAtTheirRadianceUnderTheHalfLimit) {
    bool sChanged, cChanged;
    float sigma = 1e15f;  // what alpha = 1 (infinite density) becomes on load
    openvdb::Vec3s c(2.f, 1.f, 0.f);
    clampForDcc(sigma, c, kDccMaxValue, sChanged, cChanged);
    EXPECT_TRUE(sChanged);
    EXPECT_FALSE(cChanged);
    EXPECT_FLOAT_EQ(sigma, kDccMaxValue / 2);  // emission sigma * 2 = 65504 exactly
    EXPECT_EQ(c, openvdb::Vec3s(2.f, 1.f, 0.f));
    sigma = 10.f;
    c = openvdb::Vec3s(1e6f, 0.5f, 0.f);
    clampForDcc(sigma, c, kDccMaxValue, sChanged, cChanged);
    EXPECT_TRUE(cChanged);
    EXPECT_FLOAT_EQ(c[0], kDccMaxValue);
    EXPECT_FLOAT_EQ(sigma, 1.f);  // 65504 / 65504
    sigma = 50.f;
    c = openvdb::Vec3s(3.f);
    clampForDcc(sigma, c, kDccMaxValue, sChanged, cChanged);
    EXPECT_FALSE(sChanged || cChanged);  // ordinary values pass untouched
}

TEST(DccExport, WritesOneFilePerLevelWithTheProgramsNamesTypesAndAxes) {
    const LightingVolume volume = makeExampleVolume(3, 32);
    for (Dcc dcc : {Dcc::Blender, Dcc::Houdini}) {
        const DccConvention conv = dccConvention(dcc);
        const fs::path dir = freshDir(conv.name);
        const DccExportReport report = exportForDcc(volume, dir.string(), {dcc});
        EXPECT_FALSE(report.clamp.changedAnything());
        ASSERT_EQ(report.files.size(), 3u);
        EXPECT_TRUE(fs::is_regular_file(dir / "manifest.json"));
        for (int k = 0; k < 3; ++k) {
            const auto grids = readAll(dir / dccLevelFileName(k));
            auto density = openvdb::gridPtrCast<openvdb::FloatGrid>(byName(grids, "density"));
            ASSERT_TRUE(density) << conv.name;
            EXPECT_EQ(density->getGridClass(), openvdb::GRID_FOG_VOLUME);
            auto color = openvdb::gridPtrCast<openvdb::Vec3SGrid>(byName(grids, conv.colorGrid));
            ASSERT_TRUE(color) << conv.colorGrid;
            EXPECT_EQ(color->getVectorType(), openvdb::VEC_INVARIANT);
            if (conv.splitEmission) {
                for (const char* name : kDccEmissionChannelGrids)
                    EXPECT_TRUE(openvdb::gridPtrCast<openvdb::FloatGrid>(byName(grids, name)))
                        << name;
            } else {
                auto emission = openvdb::gridPtrCast<openvdb::Vec3SGrid>(byName(grids, "emission"));
                ASSERT_TRUE(emission);
                EXPECT_EQ(emission->getVectorType(), openvdb::VEC_INVARIANT);
            }
            // Every voxel sits where the rotation says, in the program's world (Blender: with
            // its half-voxel cell convention undone by the index shift).
            const auto& src = volume.levels[k];
            for (const openvdb::Coord ijk :
                 {openvdb::Coord(0), openvdb::Coord(3, 7, 11), openvdb::Coord(31)}) {
                const Vec3d expect = conv.worldToDcc * src.transform().indexToWorld(ijk);
                const Vec3d got =
                    density->transform().indexToWorld(ijk.asVec3d() + Vec3d(-conv.indexShift));
                EXPECT_TRUE(got.eq(expect, 1e-9))
                    << conv.name << " level " << k << " " << ijk << ": " << got << " vs " << expect;
            }
            EXPECT_EQ(density->activeVoxelCount(), report.activeVoxels[k]);
        }
        fs::remove_all(dir);
    }
}

TEST(DccExport, ClampsInfiniteDensityWithAWarningAndAllowsRenderableValues) {
    LightingVolume volume = makeExampleVolume(2, 8);
    volume.levels[1].density->tree().setValueOn(openvdb::Coord(4), 1e15f);  // alpha = 1
    volume.levels[1].color->tree().setValueOn(openvdb::Coord(4), openvdb::Vec3s(4.f, 0.f, 0.f));
    const fs::path dir = freshDir("clamp");
    const DccExportReport report = exportForDcc(volume, dir.string(), {Dcc::Houdini});
    EXPECT_EQ(report.clamp.densityClamped, 1u);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("clamped"), std::string::npos);
    const auto grids = readAll(dir / dccLevelFileName(1));
    auto density = openvdb::gridPtrCast<openvdb::FloatGrid>(byName(grids, "density"));
    auto emission = openvdb::gridPtrCast<openvdb::Vec3SGrid>(byName(grids, "emission"));
    EXPECT_FLOAT_EQ(density->tree().getValue(openvdb::Coord(4)), kDccMaxValue / 4);
    EXPECT_FLOAT_EQ(emission->tree().getValue(openvdb::Coord(4))[0], kDccMaxValue);
    for (auto it = density->cbeginValueOn(); it; ++it) ASSERT_LE(*it, kDccMaxValue);
    fs::remove_all(dir);
}

TEST(DccExport, NeverOverwritesSomethingElseNorLeavesTemporaries) {
    const LightingVolume volume = makeExampleVolume(2, 8);
    const fs::path dir = freshDir("overwrite");
    fs::create_directories(dir);
    std::ofstream(dir / "precious.txt") << "keep me";
    EXPECT_THROW(exportForDcc(volume, dir.string(), {}), FileError);
    EXPECT_TRUE(fs::exists(dir / "precious.txt"));
    fs::remove_all(dir);
    // An earlier export (perhaps edited) is kept, unless replacing is asked for; then it is
    // replaced whole.
    exportForDcc(makeExampleVolume(3, 8), dir.string(), {});
    EXPECT_THROW(exportForDcc(volume, dir.string(), {}), FileError);
    EXPECT_TRUE(fs::exists(dir / dccLevelFileName(2)));
    DccExportOptions replace;
    replace.replaceExisting = true;
    exportForDcc(volume, dir.string(), replace);
    EXPECT_FALSE(fs::exists(dir / dccLevelFileName(2)));
    EXPECT_THROW(exportForDcc(volume, (dir / "no" / "such").string(), {}), FileError);
    for (const auto& e : fs::directory_iterator(dir.parent_path()))
        EXPECT_EQ(e.path().filename().string().find("." + dir.filename().string() + ".tmp"),
                  std::string::npos)
            << e.path();
    fs::remove_all(dir);
}

TEST(DccImport, RoundTripRendersLikeTheOriginal) {
    const LightingVolume volume = makeExampleVolume(3, 32);
    LightingVolume canonical;  // what import rebuilds: shells, refilled from finer levels
    canonical.levels = makeShells(volume);
    fillCoveredFromFiner(canonical);
    for (Dcc dcc : {Dcc::Blender, Dcc::Houdini}) {
        const fs::path dir = freshDir("round_trip_" + dccConvention(dcc).name);
        exportForDcc(volume, dir.string(), {dcc});
        DccImportReport report;
        const LightingVolume back = importFromDcc(dir.string(), dcc, &report);
        EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
        EXPECT_TRUE(report.notes.empty()) << report.notes.front();  // nothing was edited
        EXPECT_FALSE(report.mpi.has_value());
        ASSERT_EQ(back.levels.size(), 3u);
        ASSERT_TRUE(back.layout.has_value());  // still the nested layout
        EXPECT_EQ(*back.layout, *volume.layout);
        for (int k = 0; k < 3; ++k) {
            EXPECT_TRUE(back.levels[k].transform() == volume.levels[k].transform())
                << "level " << k;
            EXPECT_EQ(back.levels[k].domain, volume.levels[k].domain);
        }
        for (const Vec3d at : {Vec3d(0, 0, 2), Vec3d(0.2, 0.1, 0.45)}) {
            const ImageRGB a = renderEnvmap(RenderVolume(canonical), at, {64, 32, MarchOptions{}});
            const ImageRGB b = renderEnvmap(RenderVolume(back), at, {64, 32, MarchOptions{}});
            double worst = 0;
            for (std::size_t i = 0; i < a.pixels.size(); ++i)
                worst = std::max(worst, double(std::abs(a.pixels[i] - b.pixels[i])) /
                                            std::max(1e-3f, a.pixels[i]));
            EXPECT_LT(worst, 1e-5)
                << dccConvention(dcc).name << " at " << at;  // exact up to float rounding
            const ImageRGB original =
                renderEnvmap(RenderVolume(volume), at, {64, 32, MarchOptions{}});
            EXPECT_GT(psnr(b, original), 45.0);
        }
        fs::remove_all(dir);
    }
}

TEST(DccImport, RejectsWhatIsNotAnExportWithOneClearError) {
    const fs::path dir = freshDir("bad");
    EXPECT_THROW(importFromDcc(dir.string(), Dcc::Blender), FileError);  // missing
    fs::create_directories(dir);
    EXPECT_THROW(importFromDcc(dir.string(), Dcc::Blender), FileError);  // no manifest
    fs::remove_all(dir);
    exportForDcc(makeExampleVolume(2, 8), dir.string(), {Dcc::Houdini});
    try {
        importFromDcc(dir.string(), Dcc::Blender);
        ADD_FAILURE() << "importing a Houdini export as Blender must fail";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("houdini"), std::string::npos) << e.what();
    }
    // A level file whose density is the wrong type.
    auto vec = openvdb::Vec3SGrid::create();
    vec->setName("density");
    openvdb::io::File((dir / dccLevelFileName(1)).string()).write({vec});
    try {
        importFromDcc(dir.string(), Dcc::Houdini);
        ADD_FAILURE() << "a Vec3SGrid density must be rejected";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("expected a FloatGrid"), std::string::npos)
            << e.what();
    }
    fs::remove(dir / dccLevelFileName(1));
    EXPECT_THROW(importFromDcc(dir.string(), Dcc::Houdini), FileError);  // missing level file
    fs::remove_all(dir);
}

}  // namespace
}  // namespace lh
