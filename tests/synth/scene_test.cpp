#include "synth/scene.h"

#include "core/errors.h"

#include "core/random.h"
#include "synth/scene_json.h"
#include "tests/synth/synth_test_scenes.h"

#include <gtest/gtest.h>

namespace lh::synth {
namespace {

Primitive shape(Shape s, const Vec3d& half) {
    Primitive p;
    p.shape = s;
    p.half = half;
    p.centre = Vec3d(0.3, -0.2, 1.0);
    const double c = std::cos(0.4), sn = std::sin(0.4);
    p.rotation = Mat3d(c, 0.0, sn, 0.0, 1.0, 0.0, -sn, 0.0, c);
    return p;
}

TEST(SynthScene, SurfaceParameterisationRoundTrips) {
    for (const Primitive& p : {shape(Shape::Box, Vec3d(0.5, 0.3, 0.2)), shape(Shape::Sphere, Vec3d(0.4)),
                               shape(Shape::Cylinder, Vec3d(0.3, 0.5, 0))}) {
        Random rng(3);
        for (int f = 0; f < faceCount(p); ++f)
            for (int i = 0; i < 20; ++i) {
                const FaceRange r = faceRange(p, f);
                const double u = rng.uniform(r.u0, r.u1), v = rng.uniform(r.v0, r.v1);
                // Cylinder caps: stay inside the disc, away from the rim where faces meet.
                if (p.shape == Shape::Cylinder && f > 0 && std::hypot(u, v) > 0.9 * p.half.x()) continue;
                const SurfacePoint a = surfaceAt(p, 0, f, u, v);
                // On the surface, with the outward normal, and found again by projection.
                EXPECT_NEAR(signedDistance(p, a.position), 0.0, 1e-9);
                EXPECT_GT(signedDistance(p, a.position + a.normal * 0.01), 0.0);
                const SurfacePoint b = nearestSurfacePoint(p, 0, a.position + a.normal * 0.003);
                EXPECT_NEAR((b.position - a.position).length(), 0.0, 1e-6);
            }
    }
}

TEST(SynthScene, RoomIsSolidOutsideAndFreeInside) {
    const Scene s = test::blackRoom();
    EXPECT_NEAR(s.distanceToSolid(Vec3d(0, 0, 0)), 1.5, 1e-12);   // nearest: floor/ceiling
    EXPECT_NEAR(s.distanceToSolid(Vec3d(0, 0, 3.2)), -0.2, 1e-12);  // behind the back wall
    EXPECT_EQ(s.solidAt(Vec3d(0, 0, 0)), -1);
    EXPECT_EQ(s.solidAt(Vec3d(2.5, 0, 0)), 0);
    const SurfacePoint w = nearestSurfacePoint(s.primitives[0], 0, Vec3d(1.9, 0.1, 0.2));
    EXPECT_NEAR(w.position.x(), 2.0, 1e-12);
    EXPECT_NEAR(w.normal.x(), -1.0, 1e-12);  // the room's faces point inwards
}

TEST(SynthScene, JsonRoundTripIsExact) {
    Scene s = test::blackRoom();
    s.primitives.push_back(test::faceQuad(s.primitives[0], 5, Vec3d(3, 2, 1)));
    s.primitives.push_back(shape(Shape::Cylinder, Vec3d(0.3, 0.5, 0)));
    s.primitives.back().texture.kind = TextureKind::Wood;
    s.exposure = 0.37;
    BakeOptions bake;
    bake.gatherRays = 16;
    BakeOptions back;
    const Scene r = sceneFromJson(sceneToJson(s, bake), "test", &back);
    ASSERT_EQ(r.primitives.size(), s.primitives.size());
    EXPECT_EQ(r.primitives[1].radiance, s.primitives[1].radiance);
    EXPECT_EQ(r.primitives[2].rotation, s.primitives[2].rotation);
    EXPECT_EQ(r.primitives[2].texture.kind, TextureKind::Wood);
    EXPECT_EQ(r.exposure, 0.37);
    EXPECT_EQ(back.gatherRays, 16);
    EXPECT_THROW(sceneFromJson("{\"seed\": 1}", "bad.json"), FileError);
}

}  // namespace
}  // namespace lh::synth
