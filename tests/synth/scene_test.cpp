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
    for (const Primitive& p :
         {shape(Shape::Box, Vec3d(0.5, 0.3, 0.2)), shape(Shape::Sphere, Vec3d(0.4)),
          shape(Shape::Cylinder, Vec3d(0.3, 0.5, 0))}) {
        Random rng(3);
        for (int f = 0; f < faceCount(p); ++f)
            for (int i = 0; i < 20; ++i) {
                const FaceRange r = faceRange(p, f);
                const double u = rng.uniform(r.u0, r.u1), v = rng.uniform(r.v0, r.v1);
                // Cylinder caps: stay inside the disc, away from the rim where faces meet.
                if (p.shape == Shape::Cylinder && f > 0 && std::hypot(u, v) > 0.9 * p.half.x())
                    continue;
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
    EXPECT_NEAR(s.distanceToSolid(Vec3d(0, 0, 0)), 1.5, 1e-12);     // nearest: floor/ceiling
    EXPECT_NEAR(s.distanceToSolid(Vec3d(0, 0, 3.2)), -0.2, 1e-12);  // behind the back wall
    EXPECT_EQ(s.solidAt(Vec3d(0, 0, 0)), -1);
    EXPECT_EQ(s.solidAt(Vec3d(2.5, 0, 0)), 0);
    const SurfacePoint w = nearestSurfacePoint(s.primitives[0], 0, Vec3d(1.9, 0.1, 0.2));
    EXPECT_NEAR(w.position.x(), 2.0, 1e-12);
    EXPECT_NEAR(w.normal.x(), -1.0, 1e-12);  // the room's faces point inwards
}

// Brick in the texture's units (scene.h): q = local / scale + 0.37, rows kBrickRowHeight high,
// every other row shifted by half a brick, mortar kMortarWidth wide centred on the joints.
TEST(SynthTexture, BrickShowsMortarOnItsJointsAndBrickInItsCentres) {
    Texture t;
    t.kind = TextureKind::Brick;
    t.colorA = Vec3d(0.6, 0.2, 0.1);  // brick
    t.colorB = Vec3d(0.7, 0.7, 0.7);  // mortar
    t.scale = 0.4;
    t.noiseSeed = 9;
    const double shift = 0.37;
    const auto local = [&](double qAlong, double qRow) {
        return (Vec3d(qAlong, qRow, 0.0) - Vec3d(shift)) * t.scale;
    };
    const Vec3d wallNormal(0, 0, 1);  // a vertical face: rows across y, bricks along x
    const auto isBrick = [&](const Vec3d& a) {
        for (int c = 0; c < 3; ++c)
            if (a[c] < 0.8 * t.colorA[c] - 1e-12 || a[c] > t.colorA[c] + 1e-12) return false;
        return true;
    };
    for (int row = -3; row <= 3; ++row) {
        const double rowCentre = (row + 0.5) * kBrickRowHeight, offset = (row & 1) ? 0.5 : 0.0;
        for (int column = -2; column <= 2; ++column) {
            // Bed joint (between rows) and head joint (between bricks of this row): mortar.
            const Vec3d bed = local(column + 0.3, row * kBrickRowHeight + 0.3 * kMortarWidth);
            EXPECT_EQ(t.albedo(bed, wallNormal), t.colorB) << row << "," << column;
            const Vec3d head = local(column - offset + 0.3 * kMortarWidth, rowCentre);
            EXPECT_EQ(t.albedo(head, wallNormal), t.colorB) << row << "," << column;
            // Brick centre: the brick's colour, darkened by at most 20%.
            EXPECT_TRUE(isBrick(t.albedo(local(column - offset + 0.5, rowCentre), wallNormal)))
                << row << "," << column;
            // Running bond: the row above has a brick centre over this row's head joint.
            EXPECT_TRUE(
                isBrick(t.albedo(local(column - offset, rowCentre + kBrickRowHeight), wallNormal)));
            // Just inside the mortar's edge is brick.
            EXPECT_TRUE(isBrick(
                t.albedo(local(column - offset + 0.6 * kMortarWidth, rowCentre), wallNormal)));
        }
    }
    // A floor (normal along y) lays its rows across z: a joint at constant z is mortar for
    // every x, whatever the floor's height.
    for (double x : {-0.31, 0.05, 0.77})
        for (double y : {0.0, 0.123})
            EXPECT_EQ(t.albedo(Vec3d(x, y, (kBrickRowHeight - shift) * t.scale), Vec3d(0, -1, 0)),
                      t.colorB);
}

TEST(SynthTexture, BandsAndRingsSpanTheirTwoColours) {
    Texture t;
    t.colorA = Vec3d(0.1);
    t.colorB = Vec3d(0.9);
    t.scale = 0.5;
    const Vec3d n(0, 0, 1);
    // Rings: shells about q = 0, i.e. local = -0.37 scale; colour B at |q| = 1/4 (sin = 1).
    t.kind = TextureKind::Rings;
    const Vec3d origin = Vec3d(-0.37) * t.scale;
    EXPECT_NEAR(t.albedo(origin, n).x(), 0.5, 1e-12);
    EXPECT_NEAR(t.albedo(origin + Vec3d(0.25 * t.scale, 0, 0), n).x(), 0.9, 1e-12);
    EXPECT_NEAR(t.albedo(origin + Vec3d(0, 0, 0.75 * t.scale), n).x(), 0.1, 1e-12);
    // Bands: constant across the plane x + y + z = const, one period per scale along (1,1,1).
    t.kind = TextureKind::Bands;
    const Vec3d p(0.1, 0.2, 0.3);
    EXPECT_NEAR(t.albedo(p, n).x(), t.albedo(p + Vec3d(0.2, -0.1, -0.1), n).x(), 1e-12);
    EXPECT_NEAR(t.albedo(p, n).x(), t.albedo(p + Vec3d(1, 1, 1).unit() * t.scale, n).x(), 1e-12);
    EXPECT_GT(
        std::abs(t.albedo(p, n).x() - t.albedo(p + Vec3d(1, 1, 1).unit() * (0.5 * t.scale), n).x()),
        0.1);
}

TEST(SynthScene, JsonRoundTripIsExact) {
    Scene s = test::blackRoom();
    s.primitives.push_back(test::faceQuad(s.primitives[0], 5, Vec3d(3, 2, 1)));
    s.primitives.push_back(shape(Shape::Cylinder, Vec3d(0.3, 0.5, 0)));
    s.primitives.back().texture.kind = TextureKind::Wood;
    Primitive metal = shape(Shape::Sphere, Vec3d(0.25));
    metal.texture.kind = TextureKind::Brick;
    metal.texture.noiseSeed = 77;
    metal.material.kind = MaterialKind::Metal;
    metal.material.f0 = Vec3d(0.91, 0.72, 0.45);
    metal.material.roughness = 0.13;
    s.primitives.push_back(metal);
    s.primitives[0].faceTextures = {Texture{}, Texture{}};
    s.primitives[0].faceTextures[1].kind = TextureKind::Rings;
    s.exposure = 0.37;
    BakeOptions bake;
    bake.gatherRays = 16;
    BakeOptions back;
    const Scene r = sceneFromJson(sceneToJson(s, bake), "test", &back);
    ASSERT_EQ(r.primitives.size(), s.primitives.size());
    EXPECT_EQ(r.primitives[1].radiance, s.primitives[1].radiance);
    EXPECT_EQ(r.primitives[2].rotation, s.primitives[2].rotation);
    EXPECT_EQ(r.primitives[2].texture.kind, TextureKind::Wood);
    EXPECT_EQ(r.primitives[2].material.kind, MaterialKind::Diffuse);
    EXPECT_EQ(r.primitives[3].texture.kind, TextureKind::Brick);
    EXPECT_EQ(r.primitives[3].texture.noiseSeed, 77u);
    EXPECT_EQ(r.primitives[3].material.kind, MaterialKind::Metal);
    EXPECT_EQ(r.primitives[3].material.f0, Vec3d(0.91, 0.72, 0.45));
    EXPECT_EQ(r.primitives[3].material.roughness, 0.13);
    ASSERT_EQ(r.primitives[0].faceTextures.size(), 2u);
    EXPECT_EQ(r.primitives[0].faceTextures[1].kind, TextureKind::Rings);
    // The text is a fixed point: everything written is read back.
    EXPECT_EQ(sceneToJson(r, back), sceneToJson(s, bake));
    EXPECT_EQ(r.exposure, 0.37);
    EXPECT_EQ(back.gatherRays, 16);
    EXPECT_THROW(sceneFromJson("{\"seed\": 1}", "bad.json"), FileError);
}

}  // namespace
}  // namespace lh::synth
