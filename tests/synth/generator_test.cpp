// The scene generator's ranges, shaped after the evaluation rooms, over many seeds.
#include "synth/scene_generator.h"

#include "synth/scene_json.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh::synth {
namespace {

const std::vector<std::string> kPanoramas = {"city.exr", "forest.exr"};

int countLabel(const Scene& s, const std::string& label) {
    int n = 0;
    for (const Primitive& p : s.primitives) n += p.label == label;
    return n;
}

TEST(SceneGenerator, RoomsCameraAndContentsStayInTheirRangesOver60Seeds) {
    int glossy = 0, metal = 0, bricks = 0, bandsOrRings = 0, lamps = 0, panels = 0,
        panelWindows = 0;
    for (uint64_t seed = 0; seed < 60; ++seed) {
        const GeneratedScene g = generateScene(seed, kPanoramas, 128, 96);
        const Scene& s = g.scene;
        EXPECT_EQ(s.generatorVersion, kGeneratorVersion);
        const Primitive& room = s.primitives[s.roomIndex];
        ASSERT_TRUE(room.inverted);
        // Width (x), height (y, down) and depth (z) of the room, metres.
        EXPECT_GE(2 * room.half.x(), 3.0);
        EXPECT_LE(2 * room.half.x(), 8.0);
        EXPECT_GE(2 * room.half.y(), 2.4);
        EXPECT_LE(2 * room.half.y(), 3.5);
        EXPECT_GE(2 * room.half.z(), 4.0);
        EXPECT_LE(2 * room.half.z(), 10.0);

        // The reference camera (the world origin) in the room's frame: 1.2-1.8 m above the
        // floor (y = +half.y), its optical axis within 35 degrees of the depth axis and level
        // within 10 degrees.
        const Vec3d eye = room.toLocal(Vec3d(0.0));
        const double height = room.half.y() - eye.y();
        EXPECT_GE(height, 1.2 - 1e-9) << seed;
        EXPECT_LE(height, 1.8 + 1e-9) << seed;
        const Vec3d forward = room.rotation.transpose() * Vec3d(0, 0, 1);
        const double yaw = std::atan2(std::abs(forward.x()), std::abs(forward.z()));
        EXPECT_LE(yaw, kCameraYawSpread + 1e-9) << seed;
        EXPECT_LE(std::abs(forward.y()), std::sin(10 * M_PI / 180)) << seed;
        // In the back half along the direction it looks, so that the room lies ahead.
        EXPECT_LT(eye.z() * forward.z(), 0.05 * room.half.z()) << seed;

        const int lights = countLabel(s, "lamp") + countLabel(s, "panel");
        EXPECT_GE(lights, 1) << seed;
        EXPECT_LE(lights, 3) << seed;
        EXPECT_GE(countLabel(s, "window"), 1) << seed;
        EXPECT_LE(countLabel(s, "window"), 3) << seed;
        const int furniture =
            countLabel(s, "box") + countLabel(s, "cylinder") + countLabel(s, "sphere");
        EXPECT_GE(furniture, 3) << seed;
        EXPECT_LE(furniture, 10) << seed;
        lamps += countLabel(s, "lamp");
        panels += countLabel(s, "panel");

        for (const Primitive& p : s.primitives) {
            if (p.label == "lamp") {
                // Hanging 0.3-0.8 m below the ceiling (its centre), 5-15 cm radius.
                const double below = room.toLocal(p.centre).y() + room.half.y();
                EXPECT_GE(below, 0.3 - 1e-9);
                EXPECT_LE(below, 0.8 + 1e-9);
                EXPECT_GE(p.half.x(), 0.05);
                EXPECT_LE(p.half.x(), 0.15);
            }
            if (p.label == "window" && p.emission == Emission::Constant) ++panelWindows;
            glossy += p.material.kind == MaterialKind::Glossy;
            metal += p.material.kind == MaterialKind::Metal;
            if (p.material.isSpecular()) {
                for (int c = 0; c < 3; ++c) {
                    EXPECT_GT(p.material.f0[c], 0.0);
                    EXPECT_LT(p.material.f0[c], 1.0);
                }
                EXPECT_GE(p.material.roughness, 0.0);
                EXPECT_LE(p.material.roughness, 0.25);
            }
            std::vector<Texture> textures = p.faceTextures;
            textures.push_back(p.texture);
            for (const Texture& t : textures) {
                bricks += t.kind == TextureKind::Brick;
                bandsOrRings += t.kind == TextureKind::Bands || t.kind == TextureKind::Rings;
                for (int c = 0; c < 3; ++c) {
                    EXPECT_LT(t.colorA[c], 1.0);
                    EXPECT_LT(t.colorB[c], 1.0);
                }
            }
        }
    }
    // Every new kind of content appears among 60 rooms.
    EXPECT_GT(glossy, 5);
    EXPECT_GT(metal, 5);
    EXPECT_GT(bricks, 3);
    EXPECT_GT(bandsOrRings, 3);
    EXPECT_GT(lamps, 10);
    EXPECT_GT(panels, 10);
    EXPECT_GT(panelWindows, 0);
}

TEST(SceneGenerator, SameSeedGivesTheSameScene) {
    const BakeOptions bake;
    for (uint64_t seed : {3u, 4u})
        EXPECT_EQ(sceneToJson(generateScene(seed, kPanoramas, 64, 48).scene, bake),
                  sceneToJson(generateScene(seed, kPanoramas, 64, 48).scene, bake));
    EXPECT_NE(sceneToJson(generateScene(3, kPanoramas, 64, 48).scene, bake),
              sceneToJson(generateScene(4, kPanoramas, 64, 48).scene, bake));
}

}  // namespace
}  // namespace lh::synth
