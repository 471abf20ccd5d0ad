#include "vdb/volume_io.h"

#include "core/errors.h"
#include "tests/support/cut_mpi_file.h"
#include "tests/support/test_volumes.h"
#include "vdb/example_volume.h"

#include <openvdb/io/File.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <sys/stat.h>
#include <unistd.h>

namespace lh {
namespace {

namespace fs = std::filesystem;

std::string tempPath(const std::string& name) {
    fs::path dir = fs::temp_directory_path() / "lh_volume_io";
    fs::create_directories(dir);
    return (dir / name).string();
}

void writeGrids(const std::string& path, openvdb::GridPtrVec grids) {
    openvdb::initialize();
    openvdb::io::File(path).write(grids);
}

// Every stored value (voxels and tiles) and its active state agree.
template <typename GridT>
void expectSameGrid(const GridT& a, const GridT& b) {
    EXPECT_EQ(a.getName(), b.getName());
    EXPECT_EQ(a.transform(), b.transform());
    EXPECT_EQ(a.activeVoxelCount(), b.activeVoxelCount());
    EXPECT_EQ(a.background(), b.background());
    auto accB = b.getConstAccessor();
    std::size_t checked = 0;
    for (auto it = a.cbeginValueOn(); it; ++it, ++checked) {
        EXPECT_EQ(accB.getValue(it.getCoord()), *it);
        EXPECT_TRUE(accB.isValueOn(it.getCoord()));
    }
    EXPECT_GT(checked, 0u);
}

void expectFileError(const std::string& path, const std::string& fragment) {
    try {
        loadVolume(path);
        FAIL() << "no error loading " << path;
    } catch (const FileError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
        EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
    }
}

TEST(VolumeIo, RoundTripIsBitExact) {
    LightingVolume v = makeExampleVolume(3, 24);
    const std::string path = tempPath("roundtrip.vdb");
    saveVolume(path, v);
    LightingVolume back = loadVolume(path);
    ASSERT_EQ(back.levels.size(), v.levels.size());
    for (std::size_t k = 0; k < v.levels.size(); ++k) {
        expectSameGrid(*v.levels[k].density, *back.levels[k].density);
        expectSameGrid(*v.levels[k].color, *back.levels[k].color);
        EXPECT_EQ(back.levels[k].domain, v.levels[k].domain);
        EXPECT_EQ(back.levels[k].color->getVectorType(), openvdb::VEC_INVARIANT);
    }
    ASSERT_TRUE(back.layout.has_value());
    EXPECT_EQ(*back.layout, *v.layout);
    ASSERT_TRUE(back.refCamera.has_value());
    EXPECT_EQ(back.refCamera->fx, v.refCamera->fx);
    EXPECT_FALSE(back.shellCentre.has_value());  // the example is no shell
}

// A shell says so: the point it was collapsed around comes back; a damaged one is an error.
TEST(VolumeIo, AShellKeepsItsCentre) {
    LightingVolume v = makeExampleVolume(2, 24);
    v.shellCentre = Vec3d(0.25, -0.5, 1.75);
    const std::string path = tempPath("shell_centre.vdb");
    saveVolume(path, v);
    const LightingVolume back = loadVolume(path);
    ASSERT_TRUE(back.shellCentre.has_value());
    EXPECT_EQ(*back.shellCentre, *v.shellCentre);

    v.shellCentre = Vec3d(std::nan(""), 0.0, 0.0);
    EXPECT_THROW(saveVolume(tempPath("nan_centre.vdb"), v), InputError);
    EXPECT_FALSE(fs::exists(tempPath("nan_centre.vdb")));

    const std::string damaged = tempPath("damaged_centre.vdb");
    openvdb::MetaMap meta;
    meta.insertMeta("lighthouse_shell_centre", openvdb::Vec3DMetadata(openvdb::Vec3d(0, NAN, 0)));
    openvdb::initialize();
    openvdb::io::File(damaged).write({v.levels[0].density, v.levels[0].color}, meta);
    expectFileError(damaged, "lighthouse_shell_centre is not a finite point");
}

TEST(VolumeIo, HalfPrecisionIsSmallerAndClose) {
    LightingVolume v = makeExampleVolume(2, 24);
    const std::string full = tempPath("full.vdb"), half = tempPath("half.vdb");
    saveVolume(full, v);
    saveVolume(half, v, VolumeSaveOptions{true});
    EXPECT_LT(fs::file_size(half), fs::file_size(full));
    LightingVolume back = loadVolume(half);
    auto acc = back.levels[1].density->getConstAccessor();
    for (auto it = v.levels[1].density->cbeginValueOn(); it; ++it)
        EXPECT_NEAR(acc.getValue(it.getCoord()), *it, 1e-3 * *it);
}

// Fog with noisy values, as predicted volumes hold: rounded to 7 mantissa bits it reads back
// within 2^-8 of every value and takes far fewer bytes than the float file (Blosc stores the
// zeroed low bytes almost for free).
TEST(VolumeIo, MantissaRoundingShrinksTheFileWithinItsBound) {
    LightingVolume v = makeExampleVolume(2, 48);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> jitter(0.5f, 1.5f);
    for (auto& level : v.levels) {
        for (auto it = level.density->beginValueOn(); it; ++it) it.setValue(*it * jitter(rng));
        for (auto it = level.color->beginValueOn(); it; ++it)
            it.setValue(*it * openvdb::Vec3s(jitter(rng), jitter(rng), jitter(rng)));
    }
    const std::string full = tempPath("noisy_full.vdb"), rounded = tempPath("noisy_m7.vdb");
    saveVolume(full, v);
    VolumeSaveOptions options;
    options.mantissaBits = 7;
    saveVolume(rounded, v, options);
    EXPECT_LT(double(fs::file_size(rounded)), 0.7 * double(fs::file_size(full)))
        << "float " << fs::file_size(full) << " B";
    LightingVolume back = loadVolume(rounded);
    ASSERT_EQ(back.levels.size(), v.levels.size());
    for (std::size_t k = 0; k < v.levels.size(); ++k) {
        EXPECT_EQ(back.levels[k].density->activeVoxelCount(),
                  v.levels[k].density->activeVoxelCount());
        auto acc = back.levels[k].density->getConstAccessor();
        for (auto it = v.levels[k].density->cbeginValueOn(); it; ++it)
            ASSERT_NEAR(acc.getValue(it.getCoord()), *it, std::ldexp(*it, -8));
        auto colour = back.levels[k].color->getConstAccessor();
        for (auto it = v.levels[k].color->cbeginValueOn(); it; ++it)
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(colour.getValue(it.getCoord())[c], (*it)[c],
                            std::ldexp(std::abs((*it)[c]), -8));
    }
    // Half floats keep 10 bits: asking them for 10 or more is refused, and nothing is written.
    const std::string refused = tempPath("refused_m12.vdb");
    fs::remove(refused);
    VolumeSaveOptions halfTooMany;
    halfTooMany.halfPrecision = true, halfTooMany.mantissaBits = 12;
    EXPECT_THROW(saveVolume(refused, v, halfTooMany), InputError);
    EXPECT_FALSE(fs::exists(refused));
}

TEST(VolumeIo, NotAVdbFileIsAClearError) {
    const std::string path = tempPath("garbage.vdb");
    std::ofstream(path) << "this is not a VDB file at all, just text\n";
    expectFileError(path, "not a readable VDB");
    expectFileError(tempPath("missing.vdb"), "does not exist");
}

// Truncations and flipped bytes anywhere in a valid file: each load either works or throws
// FileError; OpenVDB's own aborts and huge allocations stay inside the probe's child process.
TEST(VolumeIo, CorruptedFilesFailCleanly) {
    const std::string good = tempPath("good.vdb");
    saveVolume(good, makeExampleVolume(2, 16));
    std::string bytes;
    {
        std::ifstream in(good, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    ASSERT_GT(bytes.size(), 1000u);
    const std::string bad = tempPath("bad.vdb");
    int failures = 0;
    for (int i = 1; i <= 40; ++i) {
        std::string corrupt = bytes;
        const std::size_t at = bytes.size() * i / 41;
        if (i % 2)
            corrupt.resize(at);  // truncated
        else
            corrupt[at] = char(corrupt[at] ^ 0x5a);  // one flipped byte
        std::ofstream(bad, std::ios::binary) << corrupt;
        try {
            loadVolume(bad);
        } catch (const FileError& e) {
            ++failures;
            EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
        }
    }
    EXPECT_GE(failures, 20);  // at least every truncation is detected
}

// A FIFO (or a device) is refused before anything reads it: reading one would wait for a
// writer for ever.
TEST(VolumeIo, AFifoIsRefusedNotWaitedOn) {
    const std::string path = tempPath("fifo_" + std::to_string(::getpid()) + ".vdb");
    fs::remove(path);
    ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
    expectFileError(path, "not a regular file");
    fs::remove(path);
}

TEST(VolumeIo, MissingColorGridNamesTheGrid) {
    const std::string path = tempPath("no_color.vdb");
    auto d = openvdb::FloatGrid::create(0.f);
    d->setName("density");
    d->tree().setValue(openvdb::Coord(0), 1.f);
    writeGrids(path, {d});
    expectFileError(path, "color");
}

// An empty density grid is reported as empty, not as missing. In our own files the level's
// domain is stored, so an empty room still loads, with no voxels.
TEST(VolumeIo, AnEmptyDensityGridIsEmptyNotMissing) {
    const std::string path = tempPath("empty_density.vdb");
    auto d = openvdb::FloatGrid::create(0.f);
    d->setName("density");
    auto c = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    c->setName("color");
    writeGrids(path, {d, c});
    expectFileError(path, "density grid 'density' is empty");
    try {
        loadVolume(path);
    } catch (const FileError& e) {
        EXPECT_EQ(std::string(e.what()).find("no FloatGrid"), std::string::npos) << e.what();
    }

    const std::string noDensity = tempPath("no_density.vdb");
    writeGrids(noDensity, {c});
    expectFileError(noDensity, "no FloatGrid 'density'");

    LightingVolume room = makeExampleVolume(2, 8);
    for (auto& level : room.levels) level.density->clear();
    const std::string ours = tempPath("empty_room.vdb");
    saveVolume(ours, room);
    const LightingVolume loaded = loadVolume(ours);
    ASSERT_EQ(loaded.levels.size(), 2u);
    EXPECT_EQ(loaded.levels[0].density->activeVoxelCount(), 0u);
}

TEST(VolumeIo, WrongGridTypeNamesGridAndType) {
    const std::string path = tempPath("wrong_type.vdb");
    auto d = openvdb::Vec3SGrid::create();
    d->setName("density_L0");
    auto c = openvdb::Vec3SGrid::create();
    c->setName("color_L0");
    writeGrids(path, {d, c});
    expectFileError(path, "density_L0");
    expectFileError(path, "FloatGrid");

    const std::string path2 = tempPath("wrong_color_type.vdb");
    auto d2 = openvdb::FloatGrid::create();
    d2->setName("density");
    d2->tree().setValue(openvdb::Coord(0), 1.f);
    auto c2 = openvdb::FloatGrid::create();
    c2->setName("color");
    writeGrids(path2, {d2, c2});
    expectFileError(path2, "Vec3SGrid");
}

TEST(VolumeIo, NonAffineTransformIsRefused) {
    const std::string path = tempPath("frustum.vdb");
    openvdb::BBoxd box(Vec3d(0), Vec3d(10));
    auto frustum = openvdb::math::Transform::createFrustumTransform(box, 0.5, 2.0, 0.1);
    auto d = openvdb::FloatGrid::create(0.f);
    d->setName("density");
    d->tree().setValue(openvdb::Coord(1), 1.f);
    d->setTransform(frustum);
    auto c = openvdb::Vec3SGrid::create();
    c->setName("color");
    c->setTransform(frustum->copy());
    writeGrids(path, {d, c});
    expectFileError(path, "non-affine");
}

TEST(VolumeIo, ForeignBlenderStyleFileLoadsAsOneLevel) {
    const std::string path = tempPath("blender_style.vdb");
    VolumeLevel level =
        test::makeLevel(0.1, Vec3d(-1), openvdb::Coord(20),
                        test::boxField(Vec3d(0.2), Vec3d(0.6), {5.f, openvdb::Vec3s(1, 0, 0)}));
    level.density->setName("density");
    level.color->setName("color");
    writeGrids(path, {level.density, level.color});
    LightingVolume v = loadVolume(path);
    ASSERT_EQ(v.levels.size(), 1u);
    EXPECT_FALSE(v.layout.has_value());
    // Without stored domain metadata the level covers its active voxels.
    EXPECT_EQ(v.levels[0].domain, level.density->evalActiveVoxelBoundingBox());
}

TEST(VolumeIo, NonFiniteValuesAreSanitisedWithWarningsOrRejected) {
    const std::string path = tempPath("nan.vdb");
    LightingVolume v = LightingVolume::fromLayout(VolumeLayout{4.0, 1, 8});
    v.fillLevel(0, [](const Vec3d&) { return MediumSample{1.f, openvdb::Vec3s(0.5f)}; });
    auto acc = v.levels[0].density->getAccessor();
    acc.setValue(openvdb::Coord(1, 1, 1), std::numeric_limits<float>::quiet_NaN());
    acc.setValue(openvdb::Coord(2, 2, 2), std::numeric_limits<float>::infinity());
    acc.setValue(openvdb::Coord(3, 3, 3), -2.f);
    v.levels[0].color->getAccessor().setValue(openvdb::Coord(4, 4, 4),
                                              openvdb::Vec3s(std::nanf(""), 1.f, -1.f));
    saveVolume(path, v);

    std::vector<std::string> warnings;
    LightingVolume back = loadVolume(path, &warnings);
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_NE(warnings[0].find("density_L0"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("1 NaN, 1 +Inf, 1 negative"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[1].find("color_L0"), std::string::npos) << warnings[1];
    auto d = back.levels[0].density->getConstAccessor();
    EXPECT_EQ(d.getValue(openvdb::Coord(1, 1, 1)), 0.f);
    EXPECT_EQ(d.getValue(openvdb::Coord(2, 2, 2)), kOpaqueDensity);
    EXPECT_EQ(d.getValue(openvdb::Coord(3, 3, 3)), 0.f);
    EXPECT_EQ(back.levels[0].color->getConstAccessor().getValue(openvdb::Coord(4, 4, 4)),
              openvdb::Vec3s(0.f, 1.f, 0.f));

    try {
        loadVolume(path, nullptr, VolumeLoadOptions{NonFinitePolicy::Reject});
        FAIL() << "strict load accepted NaN";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("density_L0"), std::string::npos) << e.what();
    }
}

TEST(VolumeIo, FailedSaveLeavesNoFile) {
    LightingVolume v = makeExampleVolume(1, 8);
    EXPECT_THROW(saveVolume("/nonexistent_lh_dir/v.vdb", v), FileError);
    EXPECT_FALSE(fs::exists("/nonexistent_lh_dir/v.vdb"));
}

TEST(VolumeIo, VolumeAndMpiShareOneFile) {
    LightingVolume v = makeExampleVolume(2, 8);
    Mpi mpi = Mpi::create(exampleCameras().ref, 1.0, 7.0, 4);
    mpi.pixel(2, 5, 6)[3] = 0.5f;
    const std::string path = tempPath("both.vdb");
    saveVdb(path, &v, &mpi);
    EXPECT_EQ(loadVolume(path).levels.size(), 2u);  // MPI grids are not mistaken for levels
    EXPECT_EQ(loadMpi(path).pixel(2, 5, 6)[3], 0.5f);
    saveVolume(path, v);
    EXPECT_THROW(loadMpi(path), FileError);
}

// One read gives the volume and, only when the file holds one, the MPI (export passes it on).
TEST(VolumeIo, LoadVolumeFileGivesTheMpiWhenThereIsOne) {
    LightingVolume v = makeExampleVolume(2, 8);
    Mpi mpi = Mpi::create(exampleCameras().ref, 1.0, 7.0, 3);
    mpi.pixel(1, 7, 2)[0] = 0.25f;
    const std::string path = tempPath("volume_file.vdb");
    saveVdb(path, &v, &mpi);
    VolumeFile both = loadVolumeFile(path);
    EXPECT_EQ(both.volume.levels.size(), 2u);
    ASSERT_TRUE(both.mpi.has_value());
    EXPECT_EQ(both.mpi->planeCount(), 3);
    EXPECT_EQ(both.mpi->pixel(1, 7, 2)[0], 0.25f);
    saveVolume(path, v);
    EXPECT_FALSE(loadVolumeFile(path).mpi.has_value());
}

// Rendering needs only the lighting volume: its grids are read and the MPI's are not
// (vdb/grid_selection.h). saveVdb writes the MPI's planes after the volume's grids, so cutting
// the file short damages only the MPI: the volume still loads, and reading the MPI says what
// is wrong.
TEST(VolumeIo, TheVolumeLoadsWithoutReadingTheMpi) {
    const std::string path = tempPath("cut_mpi.vdb");
    test::saveWithFilledMpi(path, makeExampleVolume(2, 8));
    const LightingVolume whole = loadVolume(path);
    test::cutShortInsideItsMpi(path);

    const LightingVolume cut = loadVolume(path);
    ASSERT_EQ(cut.levels.size(), whole.levels.size());
    for (std::size_t k = 0; k < cut.levels.size(); ++k) {
        expectSameGrid(*cut.levels[k].density, *whole.levels[k].density);
        expectSameGrid(*cut.levels[k].color, *whole.levels[k].color);
    }
    EXPECT_THROW(loadMpi(path), FileError);
    EXPECT_THROW(loadVolumeFile(path), FileError);
}

}  // namespace
}  // namespace lh
