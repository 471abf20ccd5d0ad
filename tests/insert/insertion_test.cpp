// Object insertion with known answers.
#include "insert/insertion.h"

#include "core/errors.h"
#include "tests/support/test_volumes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace lh {
namespace {

PinholeCamera camera(const Vec3d& position, int size = 64, double focal = 64) {
    PinholeCamera c;
    c.width = c.height = size;
    c.fx = c.fy = focal;
    c.cx = c.cy = size / 2.0;
    c.position = position;
    return c;
}

ImageRGB constantImage(int size, float value) {
    ImageRGB image(size, size);
    std::fill(image.pixels.begin(), image.pixels.end(), value);
    return image;
}

// Analytic first hit of a ray with a sphere (t, or -1).
double hitSphere(const Vec3d& o, const Vec3d& d, const Vec3d& c, double r) {
    const Vec3d oc = o - c;
    const double b = oc.dot(d), disc = b * b - (oc.lengthSqr() - r * r);
    return disc < 0 ? -1 : -b - std::sqrt(disc);
}

bool hitsBox(const Vec3d& o, const Vec3d& d, const Vec3d& lo, const Vec3d& hi) {
    double t0 = 0, t1 = 1e30;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-12) {
            if (o[a] < lo[a] || o[a] > hi[a]) return false;
            continue;
        }
        double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 <= t1;
}

InsertOptions exactOptions() {
    InsertOptions o;
    o.pixelSamples = 1;
    o.shadows = false;
    o.march.minTransmittance = 0;
    return o;
}

TEST(Insertion, MirrorSphereShowsRedBlockWhereTheReflectionLawSays) {
    const Vec3d lo(1.5, -0.5, -0.5), hi(2.5, 0.5, 0.5);
    const RenderVolume volume(test::volumeOf(
        {test::makeLevel(0.05, Vec3d(-3), openvdb::Coord(120),
                         test::boxField(lo, hi, {100.f, openvdb::Vec3s(1, 0, 0)}))}));
    const PinholeCamera cam = camera(Vec3d(0, 0, -3));
    const InsertedObject ball =
        placeObject(builtinMesh("sphere"), Material::parse("mirror"), Vec3d(0.0), 0.5);
    const ImageRGB out = insertObjects(volume, constantImage(64, 0.f), cam, {ball}, exactOptions());
    int red = 0, checked = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const Vec3d d = cam.pixelDirection(x + 0.5, y + 0.5);
            const double t = hitSphere(cam.position, d, ball.centre, 0.5);
            if (t < 0) continue;
            const Vec3d p = cam.position + d * t, n = (p - ball.centre).unit();
            const Vec3d r = d - n * (2 * d.dot(n));
            const float value = out.at(x, y)[0];
            if (value > 0.5f) {
                EXPECT_GT(n.x(), 0.0) << "red on the side facing away from +x at " << x << "," << y;
                ++red;
            }
            // Away from the block's edges (tessellated sphere, smooth normals) the reflection
            // law decides: inside a shrunken box red, outside a grown box black.
            const Vec3d margin(0.15);
            if (hitsBox(p, r, lo + margin, hi - margin)) {
                EXPECT_GT(value, 0.9f) << x << "," << y;
                ++checked;
            }
            if (!hitsBox(p, r, lo - margin, hi + margin)) {
                EXPECT_LT(value, 0.02f) << x << "," << y;
                ++checked;
            }
        }
    EXPECT_GT(red, 3);
    EXPECT_GT(checked, 300);  // pixels clear of the block's edges, all agreeing
}

TEST(Insertion, DiffuseSphereInUniformShellShadesToAlbedoTimesL) {
    const openvdb::Vec3s L(2.0f, 1.0f, 0.5f);
    const auto shell = [&](const Vec3d& p) {
        const double m = std::max({std::abs(p.x()), std::abs(p.y()), std::abs(p.z())});
        return m > 2.0 ? MediumSample{50.f, L} : MediumSample{};
    };
    const RenderVolume volume(
        test::volumeOf({test::makeLevel(0.1, Vec3d(-3), openvdb::Coord(60), shell)}));
    const PinholeCamera cam = camera(Vec3d(0, 0, -1.5));
    InsertOptions o = exactOptions();
    o.samples = 16;
    const InsertedObject ball =
        placeObject(builtinMesh("sphere"), Material::parse("diffuse:0.8,0.8,0.8"), Vec3d(0.0), 0.5);
    const ImageRGB out = insertObjects(volume, constantImage(64, 0.f), cam, {ball}, o);
    int pixels = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            if (hitSphere(cam.position, cam.pixelDirection(x + 0.5, y + 0.5), ball.centre, 0.49) <
                0)
                continue;
            // Every ray sees L (1 - exp(-50 x 1)) = L: no sampling noise; the bound covers the
            // trilinear ramp at the shell's inner face.
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(out.at(x, y)[c], 0.8 * L[c], 2e-3 * L[c]) << x << "," << y;
            ++pixels;
        }
    EXPECT_GT(pixels, 1000);
}

// Horizontal offset (pixels) of the lamp's reflection from the sphere's centre in the image.
double reflectionOffset(const RenderVolume& volume, double sphereX) {
    const PinholeCamera cam = camera(Vec3d(0, 0, -4), 128, 128);
    const InsertedObject ball =
        placeObject(builtinMesh("sphere"), Material::parse("mirror"), Vec3d(sphereX, 0, 0), 0.5);
    const ImageRGB out =
        insertObjects(volume, constantImage(128, 0.f), cam, {ball}, exactOptions());
    const double centreX = cam.cameraToPixel(cam.worldToCamera(ball.centre)).x();
    double sum = 0, weight = 0;
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x)
            if (out.at(x, y)[1] > 0.5f) sum += x + 0.5 - centreX, weight += 1;
    EXPECT_GT(weight, 0) << "no reflection of the lamp on the sphere at x = " << sphereX;
    return sum / weight;
}

TEST(Insertion, SpheresOnEitherSideOfALampReflectItInOppositeDirections) {
    const RenderVolume volume(test::volumeOf(
        {test::makeLevel(0.05, Vec3d(-3), openvdb::Coord(120),
                         test::boxField(Vec3d(-0.25, -0.25, -0.5), Vec3d(0.25, 0.25, 0.0),
                                        {100.f, openvdb::Vec3s(0, 1, 0)}))}));
    EXPECT_GT(reflectionOffset(volume, -1.2), 2.0);  // lamp to its right: seen on its right side
    EXPECT_LT(reflectionOffset(volume, +1.2), -2.0);
}

// An opaque grey wall across the view, 2 to 2.5 m in front of a camera at the origin.
RenderVolume wallAtTwoMetres() {
    return RenderVolume(test::volumeOf({test::makeLevel(
        0.05, Vec3d(-3), openvdb::Coord(120),
        test::boxField(Vec3d(-3, -3, 2.0), Vec3d(3, 3, 2.5), {80.f, openvdb::Vec3s(0.5f)}))}));
}

TEST(Insertion, ObjectBehindASceneSurfaceIsHidden) {
    const RenderVolume volume = wallAtTwoMetres();
    const PinholeCamera cam = camera(Vec3d(0.0));
    const ImageRGB photo = constantImage(64, 0.25f);
    const Material white = Material::parse("diffuse:1,1,1");
    InsertOptions o;  // defaults: shadows on, anti-aliasing on
    const ImageRGB behind = insertObjects(
        volume, photo, cam, {placeObject(builtinMesh("sphere"), white, Vec3d(0, 0, 4), 0.3)}, o);
    EXPECT_EQ(behind.pixels, photo.pixels);
    const ImageRGB front = insertObjects(
        volume, photo, cam, {placeObject(builtinMesh("sphere"), white, Vec3d(0, 0, 1), 0.3)}, o);
    EXPECT_GT(std::abs(front.at(32, 32)[0] - 0.25f), 0.05f);
}

// Each way an object can miss the picture is told apart: the reason names it.
TEST(Insertion, AnObjectTheImageDoesNotShowIsReportedWithItsReason) {
    const RenderVolume volume = wallAtTwoMetres();
    const PinholeCamera cam = camera(Vec3d(0.0));
    const ImageRGB photo = constantImage(64, 0.25f);
    const Material white = Material::parse("diffuse:1,1,1");
    const InsertOptions o = exactOptions();
    const auto reasonFor = [&](const Vec3d& at) {
        const std::vector<InsertedObject> objects = {
            placeObject(builtinMesh("sphere"), white, at, 0.3)};
        std::vector<ObjectVisibility> visibility;
        insertObjects(volume, photo, cam, objects, o, &visibility);
        EXPECT_EQ(visibility.size(), 1u);
        return hiddenReason(objects[0], cam, visibility[0]);
    };
    EXPECT_EQ(reasonFor(Vec3d(0, 0, 1)), "");  // in front of the wall: seen
    EXPECT_NE(reasonFor(Vec3d(0, 0, 4)).find("behind the scene's surface"), std::string::npos);
    EXPECT_NE(reasonFor(Vec3d(0, 0, -1)).find("behind the camera"), std::string::npos);
    EXPECT_NE(reasonFor(Vec3d(5, 0, 1)).find("outside the image"), std::string::npos);

    // Two objects on one line of sight: the far one is hidden by the near one.
    const std::vector<InsertedObject> pair = {
        placeObject(builtinMesh("sphere"), white, Vec3d(0, 0, 0.8), 0.3),
        placeObject(builtinMesh("sphere"), white, Vec3d(0, 0, 1.6), 0.1)};
    std::vector<ObjectVisibility> visibility;
    insertObjects(volume, photo, cam, pair, o, &visibility);
    ASSERT_EQ(visibility.size(), 2u);
    EXPECT_GT(visibility[0].raysVisible, 0);
    EXPECT_EQ(visibility[1].raysHit, 0);
    EXPECT_EQ(hiddenReason(pair[0], cam, visibility[0]), "");
    EXPECT_NE(hiddenReason(pair[1], cam, visibility[1]).find("another inserted object"),
              std::string::npos);
}

TEST(Insertion, MaterialsAndMeshesAreChecked) {
    EXPECT_EQ(Material::parse("glossy:0.3").kind, Material::Kind::Glossy);
    EXPECT_EQ(Material::parse("diffuse:0.1,0.2,0.3").albedo, Vec3d(0.1, 0.2, 0.3));
    for (const char* bad : {"gold", "glossy:0", "glossy:2", "glossy:x", "diffuse:1,2",
                            "diffuse:0.5,0.5,1.5", "mirror:1"})
        EXPECT_THROW(Material::parse(bad), InputError) << bad;
    EXPECT_THROW(builtinMesh("teapot"), InputError);
    EXPECT_THROW(loadMesh("/nonexistent/mesh.obj"), FileError);
    const auto path = std::filesystem::temp_directory_path() / "lh_tetra.obj";
    std::ofstream(path)
        << "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    const TriangleMesh tetra = loadMesh(path.string());
    EXPECT_EQ(tetra.triangleCount(), 4u);
    double radius = 0;
    for (const Vec3d& p : tetra.positions) radius = std::max(radius, p.length());
    EXPECT_NEAR(radius, 1.0, 1e-12);  // normalised
    for (const std::string name : {"sphere", "cube", "torus", "cylinder"})
        EXPECT_GT(builtinMesh(name).triangleCount(), 10u);
}

// tinyobjloader would read these coordinates as 0 or infinity without a word.
TEST(Insertion, AMeshWithANonFiniteVertexIsRefusedWithItsLine) {
    for (const char* bad : {"nan", "inf", "-inf", "1e999", "x"}) {
        const auto path = std::filesystem::temp_directory_path() / "lh_bad_vertex.obj";
        std::ofstream(path) << "# a triangle\nv 0 0 0\nv 1 0 0\nv 0 " << bad << " 0\nf 1 2 3\n";
        try {
            loadMesh(path.string());
            ADD_FAILURE() << "no error for a vertex coordinate '" << bad << "'";
        } catch (const FileError& e) {
            EXPECT_NE(std::string(e.what()).find("line 4: vertex coordinate '" + std::string(bad) +
                                                 "' is not a finite number"),
                      std::string::npos)
                << e.what();
        }
    }
}

}  // namespace
}  // namespace lh
