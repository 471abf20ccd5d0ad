#include "vdb/volume_layout.h"

#include "core/errors.h"

#include <gtest/gtest.h>

namespace lh {
namespace {

TEST(VolumeLayout, DefaultSideFollowsFarDepth) {
    EXPECT_DOUBLE_EQ(VolumeLayout::fromFarDepth(7.0).s0, 14.0);
    EXPECT_DOUBLE_EQ(VolumeLayout::fromFarDepth(50.0).s0, 40.0);  // capped at far = 20
    VolumeLayout l = VolumeLayout::fromFarDepth(7.0);
    EXPECT_EQ(l.levels, 5);
    EXPECT_EQ(l.resolution, 64);
}

TEST(VolumeLayout, BoxesMatchConventions) {
    VolumeLayout l{16.0, 5, 64};
    WorldBox b0 = l.box(0);
    EXPECT_EQ(b0.min, Vec3d(-8, -8, -8));
    EXPECT_EQ(b0.max, Vec3d(8, 8, 8));
    WorldBox b2 = l.box(2);  // side 4: x, y in [-2, 2], z in [0, 4]
    EXPECT_EQ(b2.min, Vec3d(-2, -2, 0));
    EXPECT_EQ(b2.max, Vec3d(2, 2, 4));
    EXPECT_DOUBLE_EQ(l.voxelSize(2), 4.0 / 64);
}

TEST(VolumeLayout, EveryLevelLiesOnVoxelBoundariesOfItsParent) {
    VolumeLayout l{14.0, 5, 64};
    for (int k = 1; k < l.levels; ++k) {
        const WorldBox child = l.box(k), parent = l.box(k - 1);
        const double v = l.voxelSize(k - 1);
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(child.min[a], parent.min[a]);
            EXPECT_LE(child.max[a], parent.max[a]);
            for (double face : {child.min[a], child.max[a]}) {
                const double cells = (face - parent.min[a]) / v;
                EXPECT_NEAR(cells, std::round(cells), 1e-9) << "level " << k << " axis " << a;
            }
        }
    }
}

TEST(VolumeLayout, TransformPutsVoxelCentresInsideTheBox) {
    VolumeLayout l{14.0, 5, 64};
    for (int k = 0; k < l.levels; ++k) {
        auto xf = l.transform(k);
        const double v = l.voxelSize(k);
        const Vec3d first = xf->indexToWorld(openvdb::Coord(0));
        const Vec3d last = xf->indexToWorld(openvdb::Coord(63));
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(first[a], l.box(k).min[a] + v / 2, 1e-12);
            EXPECT_NEAR(last[a], l.box(k).max[a] - v / 2, 1e-12);
        }
    }
}

TEST(VolumeLayout, ImpossibleLayoutsAreRefused) {
    EXPECT_THROW((VolumeLayout{-1.0, 5, 64}.validate()), InputError);
    EXPECT_THROW((VolumeLayout{10.0, 0, 64}.validate()), InputError);
    EXPECT_THROW((VolumeLayout{10.0, 5, 1}.validate()), InputError);
    EXPECT_THROW((VolumeLayout{10.0, 1, 1024}.validate()), ResourceError);
    EXPECT_THROW((VolumeLayout{10.0, 16, 512}.validate()), ResourceError);
    EXPECT_THROW(VolumeLayout::fromFarDepth(std::nan("")), InputError);
    // A far depth that would give voxels OpenVDB cannot invert is blamed on the cameras.
    try {
        VolumeLayout::fromFarDepth(2e-12);
        ADD_FAILURE() << "no error for far = 2e-12";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("near and far in cameras.json are depths in metres"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_NO_THROW(VolumeLayout::fromFarDepth(0.01));
    EXPECT_NO_THROW((VolumeLayout{10.0, 5, 64}.validate()));
}

TEST(VolumeLayout, JsonRoundTrip) {
    VolumeLayout l{13.5, 4, 32};
    EXPECT_EQ(VolumeLayout::fromJson(l.toJson(), "x"), l);
    EXPECT_THROW(VolumeLayout::fromJson("{}", "x"), FileError);
    EXPECT_EQ(VolumeLayout::fromJson(R"({"s0": 13.5, "levels": 4.0, "resolution": 32.0})", "x"), l);
}

// Counts that are not whole numbers that fit an int are refused, naming the key: 1e300 was a
// float-to-int conversion out of range (undefined behaviour, caught by UBSan in fuzz/
// dcc_manifest.cpp; fuzz/corpus/dcc_manifest/crash_layout_levels_1e300.json), 2^32 + 1 wrapped
// to a valid 1.
TEST(VolumeLayout, CountsThatAreNotWholeIntsAreRefused) {
    for (const char* bad :
         {"1e300", "-1e300", "4294967297", "18446744073709551615", "2.5", "\"4\"", "null"}) {
        const std::string json =
            std::string(R"({"s0": 13.5, "levels": )") + bad + R"(, "resolution": 32})";
        try {
            VolumeLayout::fromJson(json, "where.vdb");
            ADD_FAILURE() << "accepted " << json;
        } catch (const FileError& e) {
            EXPECT_NE(std::string(e.what()).find("where.vdb"), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace lh
