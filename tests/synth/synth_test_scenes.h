// Hand-built synthetic scenes with known answers.
#pragma once

#include "synth/scene.h"

namespace lh::synth::test {

// An empty room x in [-2, 2], y in [-1.5, 1.5], z in [-3, 3] (world = camera frame) with
// black walls (albedo 0).
inline Scene blackRoom() {
    Scene s;
    s.seed = 1;
    Primitive room;
    room.shape = Shape::Box;
    room.inverted = true;
    room.centre = Vec3d(0, 0, 0);
    room.half = Vec3d(2, 1.5, 3);
    room.texture.colorA = room.texture.colorB = Vec3d(0.0);
    room.label = "room";
    s.primitives.push_back(room);
    return s;
}

// A quad covering box face `face` of the room (0 x-, 1 x+, 2 y-, 3 y+, 4 z-, 5 z+), facing
// inwards, emitting `radiance`.
inline Primitive faceQuad(const Primitive& room, int face, const Vec3d& radiance) {
    const int a = face / 2, b = (a + 1) % 3, c = (a + 2) % 3;
    const double side = (face % 2) ? 1.0 : -1.0;
    Primitive q;
    q.shape = Shape::Quad;
    q.centre = room.centre;
    q.centre[a] += side * room.half[a];
    Vec3d ex(0.0), ey(0.0), ez(0.0);
    ex[b] = 1;
    ey[c] = 1;
    ez[a] = -side;  // into the room
    // Keep a right-handed frame: flip x if needed.
    if (ex.cross(ey).dot(ez) < 0) ex = -ex;
    q.rotation.setColumns(ex, ey, ez);
    q.half = Vec3d(room.half[b], room.half[c], 0);
    q.emission = Emission::Constant;
    q.radiance = radiance;
    q.label = "panel";
    return q;
}

}  // namespace lh::synth::test
