// Procedural indoor scenes with exact geometry (synthetic training and test data).
//
// A scene is a list of analytic primitives in the world frame (the reference camera's frame,
// OpenCV axes, metres). The room is a box seen from inside (`inverted`): free space inside,
// solid outside. Windows and emissive panels are quads lying on the room's walls ("decals"):
// they replace the wall's radiance where they cover it. Light transport treats every surface
// as diffuse, so the radiance it bakes does not depend on the view direction and matches the
// lighting-volume model exactly; glossy and metallic furniture (material.h) add a
// view-dependent reflection in the camera views only.
#pragma once

#include "core/vec.h"
#include "synth/material.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lh::synth {

// New kinds go at the end: scene.json names them, and the generator draws them by index.
enum class TextureKind { Plain, Checker, Stripes, Noise, Wood, Brick, Bands, Rings };

// Running-bond brick in units of the texture's scale (one brick's length): rows this high,
// mortar lines this wide (centred on the joints), every other row shifted by half a brick.
constexpr double kBrickRowHeight = 1.0 / 3.0;
constexpr double kMortarWidth = 0.07;

// Solid (3D) procedural albedo, evaluated in the primitive's local frame so that patterns
// move with the object. Colours are linear albedo in [0, 1).
//   Checker, Stripes (along local x), Noise (value noise), Wood (noisy rings about local y);
//   Brick: colorA bricks (each darkened by up to 20% at random) in colorB mortar, laid in
//     the face's plane: rows along local y on vertical faces, along local z on horizontal ones;
//   Bands: smooth sine bands across x + y + z; Rings: smooth spherical shells about the
//     pattern's origin (concentric circles on every face).
struct Texture {
    TextureKind kind = TextureKind::Plain;
    Vec3d colorA{0.5, 0.5, 0.5};
    Vec3d colorB{0.5, 0.5, 0.5};
    double scale = 0.5;  // pattern period, metres
    uint32_t noiseSeed = 0;

    // `local`: the point in the primitive's frame; `localNormal`: the surface normal there
    // (either sign), which only Brick uses to lay its rows in the face's plane.
    Vec3d albedo(const Vec3d& local, const Vec3d& localNormal) const;
};

enum class Shape { Box, Sphere, Cylinder, Quad };
enum class Emission { None, Constant, Window };

struct Primitive {
    Shape shape = Shape::Box;
    Vec3d centre{0.0, 0.0, 0.0};
    Mat3d rotation = Mat3d::identity();  // local -> world
    // Box: half extents. Sphere: radius = half.x. Cylinder: radius = half.x, half height =
    // half.y, axis = local y. Quad: half extents along local x, y; it faces local +z.
    Vec3d half{0.5, 0.5, 0.5};
    bool inverted = false;  // the room: free inside, solid outside, faces point inwards
    Texture texture;
    Material material;                  // diffuse unless the generator makes it glossy or metallic
    std::vector<Texture> faceTextures;  // optional, one per face (the room: walls, floor, ceiling)
    Emission emission = Emission::None;
    Vec3d radiance{0.0, 0.0, 0.0};  // Constant emission, linear
    int window = -1;                // Window emission: index into Scene::windows
    std::string label;              // "room", "table", "lamp", "window", ...

    bool isEmitter() const { return emission != Emission::None; }
    const Texture& textureFor(int face) const {
        return face < int(faceTextures.size()) ? faceTextures[face] : texture;
    }
    bool isDecal() const { return shape == Shape::Quad; }
    Vec3d toLocal(const Vec3d& world) const { return rotation.transpose() * (world - centre); }
    Vec3d toWorld(const Vec3d& local) const { return rotation * local + centre; }
};

// What a window shows: a panorama seen from `viewCentre` (the room's centre), so that its
// radiance depends on the point of the window, not on who looks at it.
struct WindowView {
    std::string panorama;  // file name in the panorama folder
    double yaw = 0;        // radians, turns the panorama about the room's up axis
    double scale = 1;      // radiance multiplier
    Vec3d viewCentre{0.0, 0.0, 0.0};
    Mat3d roomToWorld = Mat3d::identity();  // the room's axes (y down), for an upright panorama
};

// A point on a primitive's surface with its face parameterisation (see faceCount()).
struct SurfacePoint {
    int primitive = -1;
    int face = 0;
    double u = 0, v = 0;
    Vec3d position{0.0, 0.0, 0.0};
    Vec3d normal{0.0, 0.0, 0.0};  // unit, pointing into free space
};

struct Scene {
    uint64_t seed = 0;
    int generatorVersion = 1;
    std::vector<Primitive> primitives;
    std::vector<WindowView> windows;
    double exposure = 1.0;  // every radiance the scene emits or reflects is multiplied by it
    int roomIndex = 0;      // the inverted box

    // Signed distance to the nearest solid (negative inside a solid), metres. Decals are thin
    // and not solid.
    double distanceToSolid(const Vec3d& p) const;
    // The solid primitive containing p, or -1 in free space.
    int solidAt(const Vec3d& p) const;
    std::vector<int> emitters() const;  // primitives (including decals) that emit
};

// Face parameterisation. Box: 6 faces (axis a = f / 2, side = f % 2 ? + : -), (u, v) = the
// other two local coordinates in metres. Sphere: 1 face, u = azimuth, v = polar angle
// (radians). Cylinder: side (u = angle, v = local y), bottom cap, top cap (u, v = local x, z).
// Quad: 1 face, (u, v) = local x, y.
int faceCount(const Primitive& p);
struct FaceRange {
    double u0, u1, v0, v1;
    double metresPerU, metresPerV;  // surface length of one unit of u, v
    bool periodicU;
};
FaceRange faceRange(const Primitive& p, int face);
SurfacePoint surfaceAt(const Primitive& p, int index, int face, double u, double v);
// Nearest point on the primitive's surface to a world point (analytic).
SurfacePoint nearestSurfacePoint(const Primitive& p, int index, const Vec3d& world);
// Signed distance to the primitive's solid (for the room: to its outside).
double signedDistance(const Primitive& p, const Vec3d& world);
double surfaceArea(const Primitive& p);

}  // namespace lh::synth
