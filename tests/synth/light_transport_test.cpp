// Known answers for the baked light transport and the ground-truth renderers.
#include "synth/radiance_field.h"

#include "image/envmap_layout.h"
#include "synth/scene_render.h"
#include "tests/synth/synth_test_scenes.h"

#include "tests/support/test_camera.h"

#include <gtest/gtest.h>

namespace lh::synth {
namespace {

// 64x48 pinhole camera at the origin looking along +z.
PinholeCamera smallCamera() { return lh::test::centredCamera(64, 48, 40.0); }

PanoramaLibrary& panoramas() {
    static PanoramaLibrary library(LIGHTHOUSE_HDRI_DIR);
    return library;
}

// Every wall emits L: any point inside sees L everywhere, and a diffuse sphere of albedo rho
// inside receives E = pi L, so it shines rho L (the "furnace" test).
TEST(LightTransport, FurnaceRoomIsUniformAndLitSphereShinesAlbedoTimesL) {
    Scene s = test::blackRoom();
    const Vec3d L(1.0, 0.5, 0.25);
    for (int f = 0; f < 6; ++f) s.primitives.push_back(test::faceQuad(s.primitives[0], f, L));
    Primitive ball;
    ball.shape = Shape::Sphere;
    ball.half = Vec3d(0.5);
    ball.centre = Vec3d(0, 0, 1.5);
    ball.texture.colorA = ball.texture.colorB = Vec3d(0.8);
    s.primitives.push_back(ball);
    const RayTracer tracer(s);
    const RadianceField field(s, tracer, panoramas());

    const SceneEnvmap env =
        renderSceneEnvmap(tracer, field, Vec3d(0.5, 0.3, -1.0), 120, 60, PinholeCamera{}, 1);
    double sphereSum = 0;
    int spherePixels = 0;
    for (int y = 0; y < 60; ++y)
        for (int x = 0; x < 120; ++x) {
            const Vec3d hit(env.hitPositions.at(x, y)[0], env.hitPositions.at(x, y)[1],
                            env.hitPositions.at(x, y)[2]);
            const float* p = env.radiance.at(x, y);
            if ((hit - ball.centre).length() < 0.51) {
                // Per pixel: sampling noise of 6 x 16 light samples per texel, bound 15%.
                EXPECT_NEAR(p[0], 0.8 * L.x(), 0.15 * 0.8 * L.x());
                sphereSum += p[0];
                ++spherePixels;
            } else {
                ASSERT_FLOAT_EQ(p[0], float(L.x()));
                ASSERT_FLOAT_EQ(p[1], float(L.y()));
                ASSERT_FLOAT_EQ(p[2], float(L.z()));
            }
        }
    ASSERT_GT(spherePixels, 20);
    // Averaged over the sphere the noise cancels: within 3% of rho L.
    EXPECT_NEAR(sphereSum / spherePixels, 0.8 * L.x(), 0.03 * 0.8 * L.x());
}

TEST(LightTransport, ClosedEmissiveBoxIsUniformEverywhereInside) {
    Scene s = test::blackRoom();
    const Vec3d L(0.3, 2.0, 7.5);
    for (int f = 0; f < 6; ++f) s.primitives.push_back(test::faceQuad(s.primitives[0], f, L));
    const RayTracer tracer(s);
    const RadianceField field(s, tracer, panoramas());
    for (const Vec3d& at : {Vec3d(0.0), Vec3d(1.9, -1.4, 2.9), Vec3d(-1.0, 1.0, -2.5)}) {
        const SceneEnvmap env = renderSceneEnvmap(tracer, field, at, 64, 32, smallCamera(), 2);
        for (std::size_t i = 0; i < env.radiance.pixels.size(); ++i)
            ASSERT_FLOAT_EQ(env.radiance.pixels[i], float(L[i % 3])) << at;
    }
}

TEST(LightTransport, PanelAppearsAtItsEnvmapPixels) {
    Scene s = test::blackRoom();
    Primitive panel = test::faceQuad(s.primitives[0], 5, Vec3d(5.0));  // the +z wall, ahead
    panel.half = Vec3d(0.5, 0.5, 0);
    s.primitives.push_back(panel);
    const RayTracer tracer(s);
    const RadianceField field(s, tracer, panoramas());
    const int W = 240, H = 120;
    const SceneEnvmap env = renderSceneEnvmap(tracer, field, Vec3d(0.0), W, H, PinholeCamera{}, 1);
    // The panel spans +-9.5 degrees around +z (column W/2, row H/2): +-6 pixels.
    for (int dc = -4; dc <= 4; ++dc)
        EXPECT_FLOAT_EQ(env.radiance.at(W / 2 + dc, H / 2)[0], 5.f) << dc;
    EXPECT_FLOAT_EQ(env.radiance.at(W / 2 + 12, H / 2)[0], 0.f);
    EXPECT_FLOAT_EQ(env.radiance.at(W / 2, H / 2 + 12)[0], 0.f);
    EXPECT_FLOAT_EQ(env.radiance.at(0, H / 2)[0], 0.f);  // behind: a black wall
}

TEST(LightTransport, DepthMapMatchesTheRoomsPlanes) {
    const Scene s = test::blackRoom();
    const RayTracer tracer(s);
    const PinholeCamera cam = smallCamera();
    const ImageRGB depth = renderDepth(tracer, cam);
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const Vec3d d = cam.pixelDirection(x + 0.5, y + 0.5);
            // Distance to the first of the planes x = +-2, y = +-1.5, z = 3 along d.
            double t = 3.0 / d.z();
            if (d.x() != 0) t = std::min(t, 2.0 / std::abs(d.x()));
            if (d.y() != 0) t = std::min(t, 1.5 / std::abs(d.y()));
            ASSERT_NEAR(depth.at(x, y)[0], t * d.z(), 1e-4) << x << "," << y;
        }
}

TEST(LightTransport, ObservedMaskFollowsTheReferenceFrustum) {
    Scene s = test::blackRoom();
    const RayTracer tracer(s);
    const PinholeCamera cam = smallCamera();
    const RadianceField field(s, tracer, panoramas());
    const SceneEnvmap env = renderSceneEnvmap(tracer, field, Vec3d(0, 0, 1), 120, 60, cam, 1);
    const EnvmapCoord ahead = envmapCoordinate(Vec3d(0, 0, 1), 120, 60);
    const EnvmapCoord behind = envmapCoordinate(Vec3d(0, 0, -1), 120, 60);
    EXPECT_EQ(env.observed[int(ahead.row) * 120 + int(ahead.column)], 1);
    EXPECT_EQ(env.observed[int(behind.row) * 120 + int(behind.column)], 0);
}

}  // namespace
}  // namespace lh::synth
