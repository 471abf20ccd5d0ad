// EXIF focal length -> fx, with JPEGs carrying chosen tags (tests/support/exif_jpeg.h).
#include "cameras/exif_camera.h"
#include "core/errors.h"
#include "tests/support/exif_jpeg.h"
#include "tests/support/temp_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <optional>
#include <vector>

namespace lh {
namespace {

using test::ExifTags;
using test::makeJpeg;

TEST(ExifCamera, FocalLengthIn35mmFilmGivesFxByTheDiagonal) {
    ExifTags t;
    t.focal35mm = 28;
    const std::string path = makeJpeg("exif35.jpg", 600, 400, t);
    const ExifCameraInfo info = readExifCameraInfo(path);
    EXPECT_EQ(info.width(), 600);
    EXPECT_EQ(info.height(), 400);
    ASSERT_TRUE(info.focal35mm);
    EXPECT_DOUBLE_EQ(*info.focal35mm, 28.0);
    // 28 mm on the 36 x 24 mm frame (diagonal 43.2666 mm) spread over a 721.11 px diagonal.
    const double expected = 28.0 * std::hypot(600.0, 400.0) / std::hypot(36.0, 24.0);
    EXPECT_NEAR(exifFocalPixels(info, path), expected, 1e-9);
    // 3:2, like the 36 x 24 frame: the same as by the width.
    EXPECT_NEAR(exifFocalPixels(info, path), 28.0 / 36.0 * 600.0, 1e-9);
}

TEST(ExifCamera, FocalLengthAndFocalPlaneResolutionGiveFx) {
    ExifTags t;
    t.focalMm = 4.25;
    t.planeXRes = 2000;  // pixels per cm: 200 per mm
    t.planeUnit = 3;
    const std::string path = makeJpeg("exifplane.jpg", 640, 480, t);
    EXPECT_NEAR(exifFocalPixels(readExifCameraInfo(path), path), 4.25 * 200.0, 1e-9);
    // Inches (unit 2, the EXIF default): 5080 per inch is 200 per mm again.
    t.planeXRes = 5080;
    t.planeUnit = 2;
    const std::string inch = makeJpeg("exifinch.jpg", 640, 480, t);
    EXPECT_NEAR(exifFocalPixels(readExifCameraInfo(inch), inch), 850.0, 1e-9);
    // Captured at 1280 px wide, stored at 640: half the pixels per mm.
    t.pixelXDimension = 1280;
    const std::string resized = makeJpeg("exifresized.jpg", 640, 480, t);
    EXPECT_NEAR(exifFocalPixels(readExifCameraInfo(resized), resized), 425.0, 1e-9);
}

TEST(ExifCamera, The35mmEquivalentComesFirst) {
    ExifTags t;
    t.focal35mm = 36;
    t.focalMm = 4.25;
    t.planeXRes = 2000;
    t.planeUnit = 3;
    const std::string path = makeJpeg("exifboth.jpg", 600, 400, t);
    std::string source;
    EXPECT_NEAR(exifFocalPixels(readExifCameraInfo(path), path, &source), 600.0, 1e-9);
    EXPECT_NE(source.find("FocalLengthIn35mmFilm"), std::string::npos) << source;
}

TEST(ExifCamera, OrientationSwapsTheImageSize) {
    ExifTags t;
    t.focal35mm = 28;
    t.orientation = 6;  // stored landscape, shown rotated 90 degrees: upright is portrait
    const std::string path = makeJpeg("exifrot.jpg", 600, 400, t);
    const ExifCameraInfo info = readExifCameraInfo(path);
    EXPECT_EQ(info.orientation, 6);
    EXPECT_EQ(info.width(), 400);
    EXPECT_EQ(info.height(), 600);
    ExifPairOptions o;
    o.baseline = 0.1;
    const CamerasFile c = exifStereoPair(path, path, o);
    EXPECT_EQ(c.ref.width, 400);
    EXPECT_EQ(c.ref.height, 600);
    EXPECT_DOUBLE_EQ(c.ref.cx, 200.0);
    EXPECT_DOUBLE_EQ(c.ref.cy, 300.0);
}

TEST(ExifCamera, PairPutsSrcBaselineToTheRightAndCentresThePrincipalPoint) {
    ExifTags t;
    t.focal35mm = 36;
    const std::string ref = makeJpeg("pair_ref.jpg", 600, 400, t);
    const std::string src = makeJpeg("pair_src.jpg", 600, 400, t);
    ExifPairOptions o;
    o.baseline = 0.065;
    std::string report;
    const CamerasFile c = exifStereoPair(ref, src, o, &report);
    EXPECT_EQ(c.ref.width, 600);
    EXPECT_NEAR(c.ref.fx, 600.0, 1e-9);
    EXPECT_NEAR(c.ref.fy, 600.0, 1e-9);
    EXPECT_DOUBLE_EQ(c.ref.cx, 300.0);
    EXPECT_DOUBLE_EQ(c.ref.cy, 200.0);
    ASSERT_TRUE(c.src);
    EXPECT_DOUBLE_EQ(c.src->position.x(), 0.065);
    EXPECT_DOUBLE_EQ(c.src->position.y(), 0.0);
    EXPECT_DOUBLE_EQ(c.src->position.z(), 0.0);
    EXPECT_EQ(c.src->rotation, Mat3d::identity());
    EXPECT_FALSE(c.near.has_value());  // left to predict's own estimate
    EXPECT_NE(report.find("FocalLengthIn35mmFilm"), std::string::npos) << report;
    // --fx replaces EXIF; --near/--far are kept.
    o.fx = 812.5;
    o.near = 0.5;
    o.far = 8.0;
    const CamerasFile d = exifStereoPair(ref, src, o);
    EXPECT_DOUBLE_EQ(d.src->fx, 812.5);
    EXPECT_DOUBLE_EQ(*d.near, 0.5);
    EXPECT_DOUBLE_EQ(*d.far, 8.0);
}

template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(ExifCameraErrors, EachBadInputHasItsMessage) {
    ExifTags t;
    t.focal35mm = 28;
    const std::string good = makeJpeg("err_good.jpg", 600, 400, t);
    const std::string other = makeJpeg("err_other.jpg", 640, 400, t);
    const std::string bare = makeJpeg("err_bare.jpg", 600, 400, std::nullopt);
    const std::string corrupt = test::uniqueTempPath("err_corrupt.jpg");
    std::ofstream(corrupt) << "not a JPEG at all";
    ExifPairOptions o;
    o.baseline = 0.1;
    EXPECT_NE(errorOf([&] { exifStereoPair(good, bare, o); }).find("no usable EXIF focal length"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { exifStereoPair(good, other, o); }).find("two photos of one size"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { exifStereoPair(good, corrupt, o); }).find("cannot read photo"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { exifStereoPair(good, "/no/such.jpg", o); }).find("does not exist"),
              std::string::npos);
    for (const double b : {0.0, -1.0, std::nan("")}) {
        o.baseline = b;
        EXPECT_NE(errorOf([&] { exifStereoPair(good, good, o); }).find("--baseline"),
                  std::string::npos);
    }
    o.baseline = 0.1;
    o.near = 5.0;
    o.far = 1.0;
    EXPECT_NE(errorOf([&] { exifStereoPair(good, good, o); }).find("smaller than --far"),
              std::string::npos);
}

}  // namespace
}  // namespace lh
