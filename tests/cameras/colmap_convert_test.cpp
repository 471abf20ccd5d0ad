// COLMAP model -> cameras.json with known answers: a model written by the test in a rotated,
// scaled and shifted world must give back the true metric cameras, from text and from binary.
#include "cameras/colmap_convert.h"
#include "cameras/colmap_model.h"
#include "core/errors.h"
#include "tests/cameras/colmap_fixture.h"
#include "tests/support/temp_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

namespace lh {
namespace {

namespace fs = std::filesystem;
using test::ColmapFixture;

std::string freshDir(const std::string& name) {
    const fs::path dir = test::uniqueTempPath("lh_cameras_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

ColmapPairOptions standardOptions(const ColmapFixture& f) {
    ColmapPairOptions o;
    o.ref = "left/ref.jpg";
    o.src = "right/src.jpg";
    o.baseline = f.images[1].centre.length();
    return o;
}

void expectMat(const Mat3d& a, const Mat3d& b, double tol) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            EXPECT_NEAR(a(i, j), b(i, j), tol) << "(" << i << "," << j << ")";
}

void expectVec(const Vec3d& a, const Vec3d& b, double tol) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tol) << "component " << i;
}

void expectStandardAnswer(const ColmapPairResult& r, const ColmapFixture& f) {
    const CamerasFile& c = r.cameras;
    // Reference: the world frame, intrinsics of camera 1 (PINHOLE) unchanged.
    expectMat(c.ref.rotation, Mat3d::identity(), 1e-12);
    expectVec(c.ref.position, Vec3d(0, 0, 0), 1e-12);
    EXPECT_EQ(c.ref.width, 640);
    EXPECT_EQ(c.ref.height, 480);
    EXPECT_DOUBLE_EQ(c.ref.fx, 500.5);
    EXPECT_DOUBLE_EQ(c.ref.fy, 501.25);
    EXPECT_DOUBLE_EQ(c.ref.cx, 320.3);
    EXPECT_DOUBLE_EQ(c.ref.cy, 239.7);
    // Source: the true pose in metres, intrinsics of camera 2 (SIMPLE_PINHOLE: fx = fy).
    ASSERT_TRUE(c.src.has_value());
    expectMat(c.src->rotation, f.images[1].rotation, 1e-9);
    expectVec(c.src->position, f.images[1].centre, 1e-9);
    EXPECT_NEAR(c.src->position.length(), f.images[1].centre.length(), 1e-12);
    EXPECT_DOUBLE_EQ(c.src->fx, 498.0);
    EXPECT_DOUBLE_EQ(c.src->fy, 498.0);
    EXPECT_DOUBLE_EQ(c.src->cx, 321.0);
    EXPECT_DOUBLE_EQ(c.src->cy, 240.5);
    // SfM units: the model's world is 3.7 times the metric one.
    EXPECT_NEAR(r.scale, 1.0 / f.worldScale, 1e-12);
    EXPECT_TRUE(r.metric);
    // 1st and 99th percentile of the 101 depths 1.00 .. 5.00 m seen by ref; the point seen
    // only by src (100 m) and the one behind ref do not count.
    EXPECT_EQ(r.depthPoints, 101);
    ASSERT_TRUE(c.near && c.far);
    EXPECT_NEAR(*c.near, 1.04, 1e-9);
    EXPECT_NEAR(*c.far, 4.96, 1e-9);
}

TEST(ColmapConvert, TextModelGivesRefIdentitySrcAtBaselineIntrinsicsKept) {
    const ColmapFixture f = test::standardFixture();
    const std::string dir = freshDir("text");
    test::writeText(f, dir);
    const ColmapModel model = readColmapModel(dir);
    EXPECT_EQ(model.images.size(), 3u);
    EXPECT_EQ(model.cameras.size(), 3u);
    expectStandardAnswer(convertColmapPair(model, standardOptions(f)), f);
}

TEST(ColmapConvert, BinaryModelGivesTheSameCamerasAsText) {
    const ColmapFixture f = test::standardFixture();
    const std::string textDir = freshDir("same_text"), binDir = freshDir("same_bin");
    test::writeText(f, textDir);
    test::writeBinary(f, binDir);
    const ColmapPairResult text = convertColmapPair(readColmapModel(textDir), standardOptions(f));
    const ColmapPairResult bin = convertColmapPair(readColmapModel(binDir), standardOptions(f));
    expectStandardAnswer(bin, f);
    // Text holds 17 significant digits: the two agree to rounding.
    expectMat(bin.cameras.src->rotation, text.cameras.src->rotation, 1e-12);
    expectVec(bin.cameras.src->position, text.cameras.src->position, 1e-12);
    EXPECT_NEAR(*bin.cameras.near, *text.cameras.near, 1e-12);
    EXPECT_NEAR(*bin.cameras.far, *text.cameras.far, 1e-12);
    EXPECT_EQ(camerasToJson(bin.cameras).size(), camerasToJson(text.cameras).size());
}

TEST(ColmapConvert, BinaryFilesArePreferredWhenBothArePresent) {
    // COLMAP reads .bin first; a broken .txt beside it must not matter.
    const ColmapFixture f = test::standardFixture();
    const std::string dir = freshDir("both");
    test::writeBinary(f, dir);
    std::ofstream(dir + "/cameras.txt") << "this is not a COLMAP file\n";
    expectStandardAnswer(convertColmapPair(readColmapModel(dir), standardOptions(f)), f);
}

TEST(ColmapConvert, FileNameAloneFindsAnImageInASubfolder) {
    const ColmapFixture f = test::standardFixture();
    const std::string dir = freshDir("basename");
    test::writeText(f, dir);
    ColmapPairOptions o = standardOptions(f);
    o.ref = "ref.jpg";
    o.src = "src.jpg";
    expectStandardAnswer(convertColmapPair(readColmapModel(dir), o), f);
}

TEST(ColmapConvert, WithoutBaselineTheSfmUnitsAreKept) {
    const ColmapFixture f = test::standardFixture();
    const std::string dir = freshDir("nobaseline");
    test::writeText(f, dir);
    ColmapPairOptions o = standardOptions(f);
    o.baseline.reset();
    const ColmapPairResult r = convertColmapPair(readColmapModel(dir), o);
    EXPECT_FALSE(r.metric);
    EXPECT_DOUBLE_EQ(r.scale, 1.0);
    expectVec(r.cameras.src->position, f.images[1].centre * f.worldScale, 1e-9);
    EXPECT_NEAR(r.sfmBaseline, f.images[1].centre.length() * f.worldScale, 1e-9);
    EXPECT_NEAR(*r.cameras.near, 1.04 * f.worldScale, 1e-9);
}

TEST(ColmapConvert, AnotherBaselineScalesPositionsAndDepthsAlike) {
    const ColmapFixture f = test::standardFixture();
    const std::string dir = freshDir("scaled");
    test::writeText(f, dir);
    ColmapPairOptions o = standardOptions(f);
    const double k = 2.5;
    o.baseline = *o.baseline * k;
    const ColmapPairResult r = convertColmapPair(readColmapModel(dir), o);
    expectVec(r.cameras.src->position, f.images[1].centre * k, 1e-9);
    EXPECT_NEAR(*r.cameras.near, 1.04 * k, 1e-9);
    EXPECT_NEAR(*r.cameras.far, 4.96 * k, 1e-9);
}

TEST(ColmapConvert, GivenNearAndFarReplaceTheEstimateAndNeedNoPoints) {
    const ColmapFixture f = test::standardFixture();
    const std::string dir = freshDir("nearfar");
    test::writeText(f, dir);
    fs::remove(dir + "/points3D.txt");
    ColmapPairOptions o = standardOptions(f);
    o.near = 0.7;
    o.far = 9.0;
    const ColmapPairResult r = convertColmapPair(readColmapModel(dir, false), o);
    EXPECT_DOUBLE_EQ(*r.cameras.near, 0.7);
    EXPECT_DOUBLE_EQ(*r.cameras.far, 9.0);
    EXPECT_EQ(r.depthPoints, 0);
}

TEST(ColmapConvert, RadialModelsWithZeroDistortionArePinholes) {
    // image_undistorter copies a camera whose distortion is zero unchanged.
    ColmapFixture f = test::standardFixture();
    f.cameras[0] = {1, "OPENCV", 4, 640, 480, {500.5, 501.25, 320.3, 239.7, 0, 0, 0, 0}};
    f.cameras[1] = {2, "SIMPLE_RADIAL", 2, 640, 480, {498.0, 321.0, 240.5, 0.0}};
    const std::string dir = freshDir("zero_distortion");
    test::writeBinary(f, dir);
    expectStandardAnswer(convertColmapPair(readColmapModel(dir), standardOptions(f)), f);
}

TEST(ColmapConvert, ConvertedFileParsesBackAsCamerasJson) {
    const ColmapFixture f = test::standardFixture();
    const std::string dir = freshDir("json");
    test::writeBinary(f, dir);
    const ColmapPairResult r = convertColmapPair(readColmapModel(dir), standardOptions(f));
    const CamerasFile back = parseCamerasJson(camerasToJson(r.cameras), "converted");
    ASSERT_TRUE(back.src);
    expectVec(back.src->position, f.images[1].centre, 1e-9);
    expectMat(back.src->rotation, f.images[1].rotation, 1e-9);
}

TEST(ColmapConvert, QuaternionIsHamiltonWithScalarFirst) {
    // 90 degrees about +z maps +x to +y; an unnormalised quaternion gives the same rotation.
    const double s = std::sqrt(0.5);
    const double q[4] = {2 * s, 0, 0, 2 * s};
    const Mat3d r = rotationFromQuaternion(q);
    expectVec(r * Vec3d(1, 0, 0), Vec3d(0, 1, 0), 1e-12);
    expectVec(r * Vec3d(0, 0, 1), Vec3d(0, 0, 1), 1e-12);
    const double zero[4] = {0, 0, 0, 0};
    EXPECT_THROW(rotationFromQuaternion(zero), InputError);
}

// ---- bad input: one clear error each ----------------------------------------------------

template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(ColmapConvertErrors, MissingImageNameListsTheModelsImages) {
    const ColmapFixture f = test::standardFixture();
    const std::string dir = freshDir("missing_name");
    test::writeText(f, dir);
    ColmapPairOptions o = standardOptions(f);
    o.src = "nothere.jpg";
    const std::string e = errorOf([&] { convertColmapPair(readColmapModel(dir), o); });
    EXPECT_NE(e.find("--src image 'nothere.jpg' is not in the COLMAP model"), std::string::npos)
        << e;
    EXPECT_NE(e.find("left/ref.jpg"), std::string::npos) << e;
}

TEST(ColmapConvertErrors, RadialModelAsksForImageUndistorter) {
    ColmapFixture f = test::standardFixture();
    f.cameras[0] = {1, "SIMPLE_RADIAL", 2, 640, 480, {500.0, 320.0, 240.0, 0.01}};
    for (const bool binary : {false, true}) {
        const std::string dir = freshDir(binary ? "radial_bin" : "radial_txt");
        binary ? test::writeBinary(f, dir) : test::writeText(f, dir);
        const std::string e =
            errorOf([&] { convertColmapPair(readColmapModel(dir), standardOptions(f)); });
        EXPECT_NE(e.find("SIMPLE_RADIAL"), std::string::npos) << e;
        EXPECT_NE(e.find("only PINHOLE and SIMPLE_PINHOLE"), std::string::npos) << e;
        EXPECT_NE(e.find("image_undistorter"), std::string::npos) << e;
    }
}

TEST(ColmapConvertErrors, BaselineMustBePositiveAndFinite) {
    const ColmapFixture f = test::standardFixture();
    const std::string dir = freshDir("baseline");
    test::writeText(f, dir);
    const ColmapModel model = readColmapModel(dir);
    for (const double b : {0.0, -0.1, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
        ColmapPairOptions o = standardOptions(f);
        o.baseline = b;
        const std::string e = errorOf([&] { convertColmapPair(model, o); });
        EXPECT_NE(e.find("--baseline must be a positive finite distance"), std::string::npos)
            << b << ": " << e;
    }
}

TEST(ColmapConvertErrors, SameImageOrSamePlaceIsAZeroBaseline) {
    ColmapFixture f = test::standardFixture();
    const std::string dir = freshDir("same");
    test::writeText(f, dir);
    ColmapPairOptions o = standardOptions(f);
    o.src = o.ref;
    EXPECT_NE(errorOf([&] { convertColmapPair(readColmapModel(dir), o); }).find("zero baseline"),
              std::string::npos);
    f.images[1].centre = Vec3d(0, 0, 0);
    const std::string dir2 = freshDir("same_place");
    test::writeText(f, dir2);
    ColmapPairOptions o2 = standardOptions(f);
    o2.baseline = 0.1;
    const std::string e = errorOf([&] { convertColmapPair(readColmapModel(dir2), o2); });
    EXPECT_NE(e.find("same place"), std::string::npos) << e;
}

TEST(ColmapConvertErrors, TooFewPointsForNearFar) {
    ColmapFixture f = test::standardFixture();
    f.images[0].points.resize(19);  // 19 points in front of ref, fewer than 20
    const std::string dir = freshDir("few");
    test::writeBinary(f, dir);
    const std::string e =
        errorOf([&] { convertColmapPair(readColmapModel(dir), standardOptions(f)); });
    EXPECT_NE(e.find("only 19 3D points"), std::string::npos) << e;
    EXPECT_NE(e.find("--near and --far"), std::string::npos) << e;
}

TEST(ColmapModelErrors, MissingFolderAndFiles) {
    EXPECT_NE(errorOf([] { readColmapModel("/no/such/colmap/model"); }).find("does not exist"),
              std::string::npos);
    const std::string empty = freshDir("empty");
    EXPECT_NE(errorOf([&] { readColmapModel(empty); }).find("cameras.txt or cameras.bin"),
              std::string::npos);
    // A workspace whose model is one folder down is pointed to.
    test::writeText(test::standardFixture(), empty + "/sparse/0");
    EXPECT_NE(errorOf([&] { readColmapModel(empty); }).find("sparse/0"), std::string::npos);
    const std::string nopoints = freshDir("nopoints");
    test::writeText(test::standardFixture(), nopoints);
    fs::remove(nopoints + "/points3D.txt");
    EXPECT_NE(errorOf([&] { readColmapModel(nopoints); }).find("points3D"), std::string::npos);
}

TEST(ColmapModelErrors, TruncatedBinaryFilesAreRefused) {
    const std::string dir = freshDir("truncated");
    test::writeBinary(test::standardFixture(), dir);
    for (const char* file : {"cameras.bin", "images.bin", "points3D.bin"}) {
        const std::string path = dir + "/" + file;
        const auto size = fs::file_size(path);
        const std::string copy = dir + "/keep.bin";
        fs::copy_file(path, copy, fs::copy_options::overwrite_existing);
        fs::resize_file(path, size - 5);
        const std::string e = errorOf([&] { readColmapModel(dir); });
        EXPECT_NE(e.find(file), std::string::npos) << e;
        EXPECT_NE(e.find("truncated or corrupt"), std::string::npos) << e;
        fs::rename(copy, path);
    }
}

TEST(ColmapModelErrors, HugeCountIsRefusedBeforeAnyAllocation) {
    const std::string dir = freshDir("huge");
    test::writeBinary(test::standardFixture(), dir);
    std::fstream f(dir + "/images.bin", std::ios::in | std::ios::out | std::ios::binary);
    const std::uint64_t huge = std::uint64_t(1) << 60;
    f.write(reinterpret_cast<const char*>(&huge), sizeof huge);
    f.close();
    const std::string e = errorOf([&] { readColmapModel(dir); });
    EXPECT_NE(e.find("does not fit in the file"), std::string::npos) << e;
}

TEST(ColmapModelErrors, UnknownModelAndGarbageText) {
    const std::string dir = freshDir("garbage");
    test::writeText(test::standardFixture(), dir);
    std::ofstream(dir + "/cameras.txt") << "1 MY_LENS 640 480 1 2 3\n";
    EXPECT_NE(errorOf([&] { readColmapModel(dir); }).find("unknown camera model 'MY_LENS'"),
              std::string::npos);
    std::ofstream(dir + "/cameras.txt") << "1 PINHOLE 640 480 500 nan 320 240\n";
    EXPECT_NE(errorOf([&] { readColmapModel(dir); }).find("not finite"), std::string::npos);
    std::ofstream(dir + "/cameras.txt") << "1 PINHOLE 640 480 500 500 320\n";
    const std::string e = errorOf([&] { readColmapModel(dir); });
    EXPECT_NE(e.find("cameras.txt', line 1"), std::string::npos) << e;

    const std::string bin = freshDir("badid");
    test::ColmapFixture f = test::standardFixture();
    f.cameras[2].modelId = 42;
    test::writeBinary(f, bin);
    EXPECT_NE(errorOf([&] { readColmapModel(bin); }).find("unknown camera model id 42"),
              std::string::npos);
}

}  // namespace
}  // namespace lh
