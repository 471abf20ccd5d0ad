// The scene generator's ranges, shaped after the evaluation rooms, over many seeds.
#include "synth/scene_generator.h"

#include "synth/scene_json.h"

#include <gtest/gtest.h>

#include <algorithm>
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

TEST(SceneGenerator, RoomLampCentresLieEvenlyAlongTheMiddleOfTheLongerAxis) {
    using Centres = std::vector<std::pair<double, double>>;
    // 4 m wide, 9 m deep: along z, at (k + 1/2) * 3 m from the back wall.
    EXPECT_EQ(roomLampCentres(4, 9, 3), (Centres{{0, -3}, {0, 0}, {0, 3}}));
    // 6 m wide, 5 m deep: along x.
    EXPECT_EQ(roomLampCentres(6, 5, 2), (Centres{{-1.5, 0}, {1.5, 0}}));
    EXPECT_EQ(roomLampCentres(7, 4, 1), (Centres{{0, 0}}));
}

// The lights' horizontal bounds in the room's frame (x, z), as the generator keeps them off
// the walls: a panel by its half-size and 0.2 m, a hanging lamp by 0.5 m.
std::pair<double, double> lightBounds(const Primitive& room, const Primitive& light) {
    if (light.label == "lamp") return {room.half.x() - 0.5, room.half.z() - 0.5};
    return {room.half.x() - light.half.x() - 0.2, room.half.z() - light.half.y() - 0.2};
}

TEST(SceneGenerator, RoomLayoutMovesOnlyTheLightsOntoTheCeilingsMiddleLine) {
    int rowsOfTwoOrMore = 0;
    for (uint64_t seed = 0; seed < 40; ++seed) {
        const Scene random = generateScene(seed, kPanoramas, 64, 48).scene;
        const Scene laidOut = generateScene(seed, kPanoramas, 64, 48, LampLayout::Room).scene;
        ASSERT_EQ(random.primitives.size(), laidOut.primitives.size()) << seed;
        const Primitive& room = laidOut.primitives[laidOut.roomIndex];
        const Primitive& randomRoom = random.primitives[random.roomIndex];
        EXPECT_EQ(room.half, randomRoom.half) << seed;

        std::vector<const Primitive*> lights;
        for (size_t i = 0; i < laidOut.primitives.size(); ++i) {
            const Primitive& p = laidOut.primitives[i];
            const Primitive& q = random.primitives[i];
            ASSERT_EQ(p.label, q.label) << seed;
            EXPECT_EQ(p.radiance, q.radiance) << seed;
            EXPECT_EQ(p.half, q.half) << seed;
            if (p.label == "lamp" || p.label == "panel") {
                lights.push_back(&p);
                // The same height under the ceiling.
                EXPECT_NEAR(room.toLocal(p.centre).y(), randomRoom.toLocal(q.centre).y(), 1e-9);
            } else if (p.label != "room") {
                // Everything else stays where it was in the room.
                EXPECT_LT((room.toLocal(p.centre) - randomRoom.toLocal(q.centre)).length(), 1e-9)
                    << seed << " " << p.label;
            }
        }
        const auto expected = roomLampCentres(2 * room.half.x(), 2 * room.half.z(), lights.size());
        ASSERT_EQ(expected.size(), lights.size());
        rowsOfTwoOrMore += lights.size() >= 2;
        for (size_t k = 0; k < lights.size(); ++k) {
            const Vec3d local = room.toLocal(lights[k]->centre);
            const auto [boundX, boundZ] = lightBounds(room, *lights[k]);
            const auto near = [&](double value, double target, double bound) {
                return value >= std::clamp(target - kLampLayoutJitter, -bound, bound) - 1e-9 &&
                       value <= std::clamp(target + kLampLayoutJitter, -bound, bound) + 1e-9;
            };
            EXPECT_TRUE(near(local.x(), expected[k].first, boundX))
                << seed << " light " << k << " x " << local.x() << " expected "
                << expected[k].first;
            EXPECT_TRUE(near(local.z(), expected[k].second, boundZ))
                << seed << " light " << k << " z " << local.z() << " expected "
                << expected[k].second;
        }
    }
    EXPECT_GT(rowsOfTwoOrMore, 10);  // the spacing, not only the centre, was checked
}

}  // namespace
}  // namespace lh::synth
