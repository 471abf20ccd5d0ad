#include "core/camera.h"
#include "core/errors.h"

#include "tests/support/test_camera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh {
namespace {

const char* kValid = R"({
  "ref": {"width": 320, "height": 240, "fx": 277.1, "fy": 277.1, "cx": 160.0, "cy": 120.0,
          "cam_to_world": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]},
  "src": {"width": 320, "height": 240, "fx": 277.1, "fy": 277.1, "cx": 160.0, "cy": 120.0,
          "cam_to_world": [[1,0,0,0.1],[0,1,0,0],[0,0,1,0],[0,0,0,1]]},
  "near": 0.8, "far": 9.5,
  "envmaps": [{"position": [0.1, 0.2, 2.0], "file": "env_0.exr"}]
})";

TEST(Camera, ResizedCameraProjectsToScaledPixels) {
    const CamerasFile c = parseCamerasJson(kValid, "test.json");
    const PinholeCamera half = c.ref.resized(160, 60);  // x by 1/2, y by 1/4
    EXPECT_EQ(half.width, 160);
    EXPECT_EQ(half.height, 60);
    const Vec3d world(0.4, -0.3, 2.5);
    const Vec3d full = c.ref.cameraToPixel(c.ref.worldToCamera(world));
    const Vec3d small = half.cameraToPixel(half.worldToCamera(world));
    EXPECT_NEAR(small.x(), full.x() * 0.5, 1e-9);
    EXPECT_NEAR(small.y(), full.y() * 0.25, 1e-9);
    // The pose is unchanged: the centre pixel looks the same way.
    const Vec3d a = c.ref.pixelDirection(160, 120), b = half.pixelDirection(80, 30);
    EXPECT_NEAR((a - b).length(), 0.0, 1e-12);
}

TEST(Camera, ProjectIntoImageKeepsWhatThePhotoShows) {
    // 320x240, f = 277.1 px, principal point at the centre: (0, 0, 2) lands on pixel
    // (160, 120) at depth 2; (0.5, 0, 1) on x = 160 + 138.55 = 298.55, inside; (1, 0, 1) on
    // x = 437.1, outside; behind the camera, on its plane, or NaN: nothing.
    const PinholeCamera c = parseCamerasJson(kValid, "test.json").ref;
    const auto centre = c.projectIntoImage(Vec3d(0.0, 0.0, 2.0));
    ASSERT_TRUE(centre.has_value());
    EXPECT_NEAR(centre->x(), 160.0, 1e-9);
    EXPECT_NEAR(centre->y(), 120.0, 1e-9);
    EXPECT_NEAR(centre->z(), 2.0, 1e-12);
    const auto edge = c.projectIntoImage(Vec3d(0.5, 0.0, 1.0));
    ASSERT_TRUE(edge.has_value());
    EXPECT_NEAR(edge->x(), 298.55, 1e-9);
    EXPECT_FALSE(c.projectIntoImage(Vec3d(1.0, 0.0, 1.0)).has_value());
    EXPECT_FALSE(c.projectIntoImage(Vec3d(0.0, 0.0, -2.0)).has_value());
    EXPECT_FALSE(c.projectIntoImage(Vec3d(0.0, 0.0, 0.0)).has_value());
    EXPECT_FALSE(c.projectIntoImage(Vec3d(std::nan(""), 0.0, 2.0)).has_value());
    // Pixel (u, v) covers [u, u + 1): of a 100x80 camera of focal 100 px, x = 0 is inside and
    // x = 100, its right edge, outside.
    const PinholeCamera small = test::centredCamera(100, 80, 100.0);
    EXPECT_TRUE(small.projectIntoImage(Vec3d(-0.5, 0.0, 1.0)).has_value());
    EXPECT_FALSE(small.projectIntoImage(Vec3d(0.5, 0.0, 1.0)).has_value());
}

TEST(Camera, ParsesConventionsExample) {
    CamerasFile c = parseCamerasJson(kValid, "test.json");
    EXPECT_EQ(c.ref.width, 320);
    EXPECT_DOUBLE_EQ(c.ref.fx, 277.1);
    ASSERT_TRUE(c.src.has_value());
    EXPECT_DOUBLE_EQ(c.src->position.x(), 0.1);
    EXPECT_DOUBLE_EQ(*c.near, 0.8);
    EXPECT_DOUBLE_EQ(*c.far, 9.5);
    ASSERT_EQ(c.envmaps.size(), 1u);
    EXPECT_DOUBLE_EQ(c.envmaps[0].position.z(), 2.0);
    EXPECT_FALSE(c.tgt.has_value());
    EXPECT_THROW(c.view("tgt"), InputError);
}

TEST(Camera, JsonRoundTrip) {
    CamerasFile c = parseCamerasJson(kValid, "test.json");
    CamerasFile back = parseCamerasJson(camerasToJson(c), "again.json");
    EXPECT_EQ(back.src->position, c.src->position);
    EXPECT_EQ(back.ref.rotation, c.ref.rotation);
    EXPECT_EQ(*back.far, *c.far);
    EXPECT_EQ(back.envmaps[0].file, "env_0.exr");
}

TEST(Camera, PrincipalPointLooksForwardAndProjectionInverts) {
    PinholeCamera cam = parseCamerasJson(kValid, "t").ref;
    Vec3d d = cam.pixelDirection(160.0, 120.0);
    EXPECT_NEAR(d.z(), 1.0, 1e-12);
    // A point 3 m away through pixel centre (10, 20) projects back to it.
    Vec3d p = cam.pixelDirection(10.5, 20.5);
    p *= 3.0 / p.z();
    Vec3d px = cam.cameraToPixel(cam.worldToCamera(p));
    EXPECT_NEAR(px.x(), 10.5, 1e-9);
    EXPECT_NEAR(px.y(), 20.5, 1e-9);
    EXPECT_NEAR(px.z(), 3.0, 1e-12);
}

TEST(Camera, RotatedPoseMapsCameraAxes) {
    PinholeCamera cam = parseCamerasJson(kValid, "t").ref;
    // Camera turned 90 degrees to the right: its forward (+z) is world +x.
    cam.rotation = Mat3d(0.0, 0.0, 1.0,  //
                         0.0, 1.0, 0.0,  //
                         -1.0, 0.0, 0.0);
    cam.position = Vec3d(1, 2, 3);
    cam.validate("rotated");
    Vec3d d = cam.pixelDirection(cam.cx, cam.cy);
    EXPECT_NEAR(d.x(), 1.0, 1e-12);
    Vec3d inCam = cam.worldToCamera(Vec3d(3, 2, 3));  // 2 m in front
    EXPECT_NEAR(inCam.z(), 2.0, 1e-12);
    EXPECT_NEAR(inCam.x(), 0.0, 1e-12);
}

void expectInputError(const std::string& json, const std::string& fragment) {
    try {
        parseCamerasJson(json, "bad.json");
        FAIL() << "no error for: " << json;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    }
}

TEST(Camera, ImpossibleCamerasAreRejected) {
    const std::string cam = R"("width": 320, "height": 240, "cx": 160, "cy": 120)";
    expectInputError("{\"ref\": {" + cam + R"(, "fx": -5, "fy": 5}})", "focal");
    expectInputError(
        "{\"ref\": {" + cam +
            R"(, "fx": 5, "fy": 5, "cam_to_world": [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}})",
        "orthonormal");
    expectInputError(
        "{\"ref\": {" + cam +
            R"(, "fx": 5, "fy": 5, "cam_to_world": [[-1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}})",
        "determinant");
    expectInputError("{\"ref\": {" + cam + R"(, "fx": 5, "fy": 5}, "near": 5, "far": 2})", "near");
    expectInputError("{\"ref\": {" + cam + R"(, "fx": 5}})", "fy");
    expectInputError(R"({"src": {}})", "ref");
    expectInputError("{\"ref\": {" + cam + R"(, "fx": 5, "fy": 5, "cam_to_world": [[1,0,0]]}})",
                     "4x4");
    expectInputError("not json at all", "JSON");
    expectInputError(R"({"ref": {"width": 0, "height": 240, "fx": 5, "fy": 5, "cx": 1, "cy": 1}})",
                     "width");
}

// A non-string envmap file escaped as json's type_error, the one-line error then naming neither
// the file nor the key ("[json.exception.type_error.302] type must be string, but is number"),
// and the fuzz target (fuzz/cameras_json.cpp) aborting on it: its corpus keeps the input
// (fuzz/corpus/cameras_json/crash_envmap_file_number.json).
TEST(Camera, AnEnvmapFileThatIsNotAStringIsAnInputError) {
    const std::string ref =
        R"("ref": {"width": 64, "height": 48, "fx": 50, "fy": 50, "cx": 32, "cy": 24})";
    for (const char* key : {"file", "position_file"})
        for (const char* value : {"3", "null", "[\"a.exr\"]", "{}"}) {
            const std::string json = "{" + ref + R"(, "envmaps": [{"position": [0, 0, 1], ")" +
                                     key + "\": " + value + "}]}";
            EXPECT_THROW(parseCamerasJson(json, "bad.json"), InputError) << json;
            expectInputError(json, std::string("'") + key + "' must be a string");
        }
}

TEST(Camera, MissingFileIsAFileError) {
    EXPECT_THROW(loadCamerasFile("/nonexistent/cameras.json"), FileError);
}

}  // namespace
}  // namespace lh
