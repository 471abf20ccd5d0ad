// Glossy and metallic surfaces: view-dependent in the camera views, view-independent in the
// baked field and the envmaps. Known answers from a ray-sphere intersection done by hand.
#include "synth/specular_shading.h"

#include "image/envmap_layout.h"
#include "synth/scene_render.h"
#include "tests/synth/synth_test_scenes.h"

#include "tests/support/test_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

namespace lh::synth {
namespace {

PanoramaLibrary& panoramas() {
    static PanoramaLibrary library(LIGHTHOUSE_HDRI_DIR);
    return library;
}

constexpr double kRadius = 0.35;
const Vec3d kMirrorCentre(-0.45, 0.0, 1.6), kDiffuseCentre(0.75, 0.0, 1.6);
constexpr double kMirrorF0 = 0.9;

// Radiance of back-wall cell (i, j): 1 m squares over the -z wall (x in [-2, 2], y in
// [-1.5, 1.5]), each with its own red level so that a reflection names the cell it shows.
Vec3d cellRadiance(int i, int j) { return Vec3d(1.0 + i + 4 * j, 0.5, 13.0 - (i + 4 * j)); }

// The black room with the tiled back wall, a mirror sphere (F0 = 0.9, no diffuse part) and a
// diffuse grey sphere, both in front of the camera at the origin.
Scene mirrorScene() {
    Scene s = test::blackRoom();
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 4; ++i) {
            Primitive q;
            q.shape = Shape::Quad;
            q.centre = Vec3d(-1.5 + i, -1.0 + j, -3.0);  // identity rotation: faces +z, inwards
            q.half = Vec3d(0.5, 0.5, 0);
            q.emission = Emission::Constant;
            q.radiance = cellRadiance(i, j);
            q.label = "panel";
            s.primitives.push_back(q);
        }
    Primitive mirror;
    mirror.shape = Shape::Sphere;
    mirror.centre = kMirrorCentre;
    mirror.half = Vec3d(kRadius);
    mirror.texture.colorA = mirror.texture.colorB = Vec3d(0.0);
    mirror.material.kind = MaterialKind::Metal;
    mirror.material.f0 = Vec3d(kMirrorF0);
    mirror.label = "sphere";
    s.primitives.push_back(mirror);
    Primitive ball = mirror;
    ball.centre = kDiffuseCentre;
    ball.texture.colorA = ball.texture.colorB = Vec3d(0.6);
    ball.material = Material{};
    s.primitives.push_back(ball);
    return s;
}

PinholeCamera camera(double x) { return lh::test::centredCamera(320, 240, 240.0, Vec3d(x, 0, 0)); }

// First t > 0 where origin + t dir meets the sphere, if it does.
std::optional<double> hitSphere(const Vec3d& origin, const Vec3d& dir, const Vec3d& centre,
                                double radius) {
    const Vec3d o = origin - centre;
    const double b = o.dot(dir), c = o.lengthSqr() - radius * radius, disc = b * b - c;
    if (disc < 0) return std::nullopt;
    const double t = -b - std::sqrt(disc);
    return t > 0 ? std::optional<double>(t) : std::nullopt;
}

struct Expected {
    Vec3d radiance;
    Vec3d point;
};

// What pixel (x, y) of `cam` shows of the mirror sphere, computed by hand; nullopt where the
// answer is not clear-cut (grazing views, reflections near a cell edge or onto the other ball).
std::optional<Expected> expectedMirrorPixel(const PinholeCamera& cam, int x, int y) {
    const Vec3d d = cam.pixelDirection(x + 0.5, y + 0.5);
    const auto t = hitSphere(cam.position, d, kMirrorCentre, kRadius);
    if (!t) return std::nullopt;
    const Vec3d p = cam.position + d * *t, n = (p - kMirrorCentre) / kRadius;
    const double cosView = -d.dot(n);
    if (cosView < 0.3) return std::nullopt;
    const Vec3d m = d + n * (2 * cosView);
    if (hitSphere(p, m, kDiffuseCentre, kRadius + 0.02)) return std::nullopt;
    // The first of the room's planes x = +-2, y = +-1.5, z = +-3 along m.
    double tWall = 1e9;
    int axis = -1;
    const double half[3] = {2.0, 1.5, 3.0};
    for (int a = 0; a < 3; ++a)
        if (m[a] != 0) {
            const double ta = ((m[a] > 0 ? half[a] : -half[a]) - p[a]) / m[a];
            if (ta < tWall) tWall = ta, axis = a;
        }
    const Vec3d w = p + m * tWall;
    Vec3d shown(0.0);  // the black walls
    if (axis == 2 && m.z() < 0) {
        const double u = w.x() + 2.0, v = w.y() + 1.5;  // cell coordinates, metres
        const double du = u - std::round(u), dv = v - std::round(v);
        if (std::abs(du) < 0.03 || std::abs(dv) < 0.03) return std::nullopt;
        shown = cellRadiance(int(std::floor(u)), int(std::floor(v)));
    } else {
        // Away from the tiled wall's edges, where black meets a cell.
        if (std::abs(std::abs(w.x()) - 2.0) < 0.03 || std::abs(std::abs(w.y()) - 1.5) < 0.03 ||
            std::abs(w.z() + 3.0) < 0.03)
            return std::nullopt;
    }
    const double fresnel = kMirrorF0 + (1 - kMirrorF0) * std::pow(1 - cosView, 5);
    return Expected{shown * fresnel, p};
}

// Pixel of `cam` that sees the world point p.
std::pair<int, int> pixelOf(const PinholeCamera& cam, const Vec3d& p) {
    const Vec3d px = cam.cameraToPixel(cam.worldToCamera(p));
    return {int(std::floor(px.x())), int(std::floor(px.y()))};
}

TEST(Specular, MirrorSphereShowsTheReflectionOfItsOwnViewAndDiffuseOneMatches) {
    const Scene s = mirrorScene();
    const RayTracer tracer(s);
    // Default bake: 64 gather rays keep the texel noise of the light the mirror sends onto
    // the ball well under the 3% the comparison below allows.
    const RadianceField field(s, tracer, panoramas());
    const PinholeCamera ref = camera(0.0), src = camera(0.15);
    const ImageRGB refImage = renderSceneView(tracer, field, ref, 1);
    const ImageRGB srcImage = renderSceneView(tracer, field, src, 1);

    int checked = 0, differing = 0;
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) {
            const auto e = expectedMirrorPixel(ref, x, y);
            if (!e) continue;
            // Known answer: F(theta) times the radiance of the cell the mirror ray meets.
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(refImage.at(x, y)[c], e->radiance[c], 0.01 * e->radiance[c] + 1e-5)
                    << x << "," << y;
            const auto [sx, sy] = pixelOf(src, e->point);
            const auto es = expectedMirrorPixel(src, sx, sy);
            if (!es || (es->point - e->point).length() > 0.01) continue;
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(srcImage.at(sx, sy)[c], es->radiance[c], 0.01 * es->radiance[c] + 1e-5)
                    << sx << "," << sy;
            ++checked;
            // The same point of the mirror, seen from 15 cm further right, reflects another cell.
            differing += std::abs(refImage.at(x, y)[0] - srcImage.at(sx, sy)[0]) > 0.5;
        }
    EXPECT_GT(checked, 400);
    EXPECT_GT(differing, 80);

    // The diffuse ball looks the same from both cameras at the same surface point (as the
    // ray tracer finds it on its sphere mesh: within 3 mm; the light turns with the normal).
    int diffuse = 0;
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) {
            const Vec3d d = ref.pixelDirection(x + 0.5, y + 0.5);
            const RayHit h = tracer.intersect(ref.position, d, 0.0);
            if (!h.hit || h.point.primitive != int(s.primitives.size()) - 1 ||
                -d.dot(h.point.normal) < 0.5)
                continue;
            const auto [sx, sy] = pixelOf(src, h.point.position);
            const RayHit hs =
                tracer.intersect(src.position, src.pixelDirection(sx + 0.5, sy + 0.5), 0.0);
            if (!hs.hit || (hs.point.position - h.point.position).length() > 0.003) continue;
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(srcImage.at(sx, sy)[c], refImage.at(x, y)[c],
                            0.03 * refImage.at(x, y)[c] + 1e-4)
                    << x << "," << y;
            ++diffuse;
        }
    EXPECT_GT(diffuse, 300);
}

TEST(Specular, BakedFieldAndEnvmapsSeeTheMirrorAsDiffuseOfEqualReflectance) {
    const Scene s = mirrorScene();
    const RayTracer tracer(s);
    BakeOptions bake;
    bake.gatherRays = 16;
    const RadianceField field(s, tracer, panoramas(), bake);
    // From the mirror's centre towards the camera: its front point.
    const RayHit hit =
        tracer.intersect(Vec3d(0.0), (kMirrorCentre - Vec3d(0, 0, kRadius)).unit(), 0.0);
    ASSERT_TRUE(hit.hit);
    ASSERT_EQ(hit.point.primitive, int(s.primitives.size()) - 2);
    const double favg = kMirrorF0 + (1 - kMirrorF0) / 21;  // hemispherical mean of Schlick's F
    EXPECT_NEAR(field.albedo(hit.point).x(), favg, 1e-12);
    EXPECT_EQ(field.textureAlbedo(hit.point), Vec3d(0.0));
    const Vec3d e = field.irradiance(hit.point);
    EXPECT_GT(e.x(), 0.1);
    EXPECT_NEAR(field.radiance(hit.point).x(), favg * e.x() / M_PI, 1e-9);

    // Two envmaps at different points show the mirror's same point with the same radiance:
    // the baked value, not a reflection (which would differ between them).
    const PinholeCamera ref = camera(0.0);
    for (const Vec3d& at : {Vec3d(-0.45, 0.0, 0.6), Vec3d(-0.2, -0.3, 0.7)}) {
        const SceneEnvmap env = renderSceneEnvmap(tracer, field, at, 240, 120, ref, 1);
        int onMirror = 0;
        for (int y = 0; y < 120; ++y)
            for (int x = 0; x < 240; ++x) {
                const Vec3d p(env.hitPositions.at(x, y)[0], env.hitPositions.at(x, y)[1],
                              env.hitPositions.at(x, y)[2]);
                if (std::abs((p - kMirrorCentre).length() - kRadius) > 1e-3) continue;
                const RayHit h = tracer.intersect(at, envmapPixelDirection(y, x, 240, 120), 0.0);
                ASSERT_TRUE(h.hit);
                ++onMirror;
                // One sample at the pixel centre, as hitPositions, so the value is exactly the
                // baked one.
                ASSERT_NEAR(env.radiance.at(x, y)[0], field.radiance(h.point).x(),
                            1e-4 + 1e-4 * field.radiance(h.point).x());
            }
        EXPECT_GT(onMirror, 50);
    }
}

}  // namespace
}  // namespace lh::synth
