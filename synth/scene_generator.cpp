#include "synth/scene_generator.h"

#include "core/errors.h"
#include "core/random.h"

#include <algorithm>
#include <cmath>

namespace lh::synth {

namespace {

// Room frame: OpenCV-like axes with y down, the floor at y = 0, the ceiling at y = -height,
// the room centred on x = z = 0.
struct RoomSize {
    double width, depth, height;  // x, z, y extents, metres
};

Vec3d hsvToLinear(double h, double s, double v) {
    const double c = v * s, hp = std::fmod(h * 6.0, 6.0),
                 x = c * (1 - std::abs(std::fmod(hp, 2.0) - 1));
    Vec3d rgb = hp < 1   ? Vec3d(c, x, 0)
                : hp < 2 ? Vec3d(x, c, 0)
                : hp < 3 ? Vec3d(0, c, x)
                : hp < 4 ? Vec3d(0, x, c)
                : hp < 5 ? Vec3d(x, 0, c)
                         : Vec3d(c, 0, x);
    rgb += Vec3d(v - c);
    for (int i = 0; i < 3; ++i) rgb[i] = std::pow(rgb[i], 2.2);  // perceptual -> linear albedo
    return rgb;
}

Vec3d randomColor(Random& rng, double minValue = 0.25, double maxValue = 0.9) {
    return hsvToLinear(rng.uniform(), rng.uniform(0.0, 0.8), rng.uniform(minValue, maxValue));
}

Texture randomTexture(Random& rng) {
    Texture t;
    t.kind = TextureKind(rng.integer(0, 7));
    t.colorA = randomColor(rng);
    t.colorB = t.colorA * rng.uniform(0.35, 0.8);  // same hue, darker: readable patterns
    if (rng.chance(0.4)) t.colorB = randomColor(rng);
    t.scale = rng.uniform(0.1, 0.8);
    t.noiseSeed = uint32_t(rng.next());
    if (t.kind == TextureKind::Brick) {
        // Bricks 0.25-0.5 m long (with their mortar), mostly red-brown in light grey mortar.
        if (rng.chance(0.7))
            t.colorA =
                hsvToLinear(rng.uniform(0.0, 0.08), rng.uniform(0.4, 0.8), rng.uniform(0.45, 0.8));
        t.colorB = hsvToLinear(rng.uniform(), rng.uniform(0.0, 0.1), rng.uniform(0.6, 0.85));
        t.scale = rng.uniform(0.25, 0.5);
    }
    return t;
}

// Furniture surfaces, as in the evaluation rooms: mostly diffuse, some glossy (varnish,
// plastic: F0 = 0.04, a mirror-like clear coat or a blurred one) and some metallic (tinted
// F0, a dark diffuse remainder). Metals replace the texture's colours.
void randomMaterial(Random& rng, Primitive& p) {
    const double u = rng.uniform();
    if (u < 0.6) return;
    Material& m = p.material;
    m.roughness = rng.chance(0.5) ? 0.0 : rng.uniform(0.04, 0.25);
    if (u < 0.8) {
        m.kind = MaterialKind::Glossy;
        m.f0 = Vec3d(0.04);
        return;
    }
    m.kind = MaterialKind::Metal;
    // Steel and aluminium (grey), brass, gold and copper (warm): 0.5-0.95 reflectance.
    m.f0 = hsvToLinear(rng.uniform(0.02, 0.14),
                       rng.chance(0.5) ? rng.uniform(0.0, 0.1) : rng.uniform(0.3, 0.6),
                       rng.uniform(0.73, 0.97));
    p.texture = Texture{};
    p.texture.colorA = p.texture.colorB = m.f0 * 0.05;
}

Texture woodTexture(Random& rng) {
    Texture t;
    t.kind = TextureKind::Wood;
    t.colorA = hsvToLinear(rng.uniform(0.05, 0.11), rng.uniform(0.4, 0.7), rng.uniform(0.45, 0.75));
    t.colorB = t.colorA * 0.55;
    t.scale = rng.uniform(0.3, 0.9);
    t.noiseSeed = uint32_t(rng.next());
    return t;
}

Mat3d rotationY(double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return Mat3d(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c);
}

Mat3d rotationX(double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return Mat3d(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c);
}

// A quad on the room's wall face `face` (0: x-, 1: x+, 4: z-, 5: z+) or ceiling (2), facing
// into the room; (along, down) is its centre in the face's in-plane coordinates.
Primitive wallQuad(const RoomSize& room, int face, double along, double alongHalf, double y,
                   double yHalf) {
    Primitive q;
    q.shape = Shape::Quad;
    q.half = Vec3d(alongHalf, yHalf, 0);
    // Local x runs along the wall, local y down the wall, local z into the room.
    switch (face) {
        case 0:
            q.centre = Vec3d(-room.width / 2, y, along);
            q.rotation = Mat3d(0.0, 0.0, 1.0, 0.0, 1.0, 0.0, -1.0, 0.0, 0.0);
            break;
        case 1:
            q.centre = Vec3d(room.width / 2, y, along);
            q.rotation = Mat3d(0.0, 0.0, -1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0);
            break;
        case 4:
            q.centre = Vec3d(along, y, -room.depth / 2);
            q.rotation = Mat3d::identity();
            break;
        case 5:
            q.centre = Vec3d(along, y, room.depth / 2);
            q.rotation = Mat3d(-1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -1.0);
            break;
        default:  // ceiling: local z points down (+y), into the room
            q.centre = Vec3d(along, -room.height, y);
            q.rotation = Mat3d(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0);
            break;
    }
    return q;
}

// Emitted radiance ranges, linear, before auto-exposure: [min, max]. For scale: the
// panoramas peak at 50 after clipping and their brightest 1% lies at 1-15. Only ratios
// survive auto-exposure; these make the brightest envmap pixels reach about 35-1200
// (median about 120) and their 99.5th percentile 0.5-60, near the evaluation rooms'
// 35-1450 (median 214) and 1.6-80.
constexpr double kPanelRadiance[2] = {30, 150};        // ceiling panels, 0.09-1 m^2
constexpr double kLampRadiance[2] = {150, 900};        // hanging spheres, 5-15 cm radius
constexpr double kWindowPanelRadiance[2] = {20, 100};  // uniform windows
constexpr double kPanoramaScale[2] = {1.0, 3.0};       // multiplier of a window's panorama
constexpr double kBrightPanelWindowChance = 0.15;
constexpr double kWhiteCeilingChance = 0.35;

double wallLength(const RoomSize& room, int face) { return face < 2 ? room.depth : room.width; }

struct Footprint {
    double x, z, radius;
};

bool overlaps(const std::vector<Footprint>& placed, const Footprint& f) {
    for (const auto& p : placed)
        if (std::hypot(p.x - f.x, p.z - f.z) < p.radius + f.radius + 0.1) return true;
    return false;
}

}  // namespace

std::vector<std::pair<double, double>> roomLampCentres(double roomWidth, double roomDepth,
                                                       int count) {
    std::vector<std::pair<double, double>> centres;
    const bool alongDepth = roomDepth >= roomWidth;
    const double length = alongDepth ? roomDepth : roomWidth;
    for (int k = 0; k < count; ++k) {
        const double along = -length / 2 + (k + 0.5) * length / count;
        centres.emplace_back(alongDepth ? 0.0 : along, alongDepth ? along : 0.0);
    }
    return centres;
}

GeneratedScene generateScene(uint64_t seed, const std::vector<std::string>& panoramas, int width,
                             int height, LampLayout lampLayout) {
    if (panoramas.empty())
        throw InputError("scene generator: no panoramas to show through windows");
    Random rng(seed);
    Scene scene;
    scene.seed = seed;
    scene.generatorVersion = kGeneratorVersion;
    // The ranges of the evaluation rooms (Blender scenes): 3-8 m wide, 4-10 m deep.
    const RoomSize room{rng.uniform(3, 8), rng.uniform(4, 10), rng.uniform(2.4, 3.5)};

    // The room: walls share one texture, the floor is wood or patterned, the ceiling plain and
    // near-white (35%) or any texture of its own. The evaluation rooms' ceilings are as often
    // tinted, textured or dark as white: relative to the photo's median, the top quarter of
    // their envmaps is 0.15-7x (typically 0.8x) where near-white ceilings made it 1-85x
    // (typically 3x), and a model trained on those painted every ceiling bright.
    Primitive shell;
    shell.shape = Shape::Box;
    shell.inverted = true;
    shell.centre = Vec3d(0, -room.height / 2, 0);
    shell.half = Vec3d(room.width / 2, room.height / 2, room.depth / 2);
    shell.label = "room";
    const Texture walls = randomTexture(rng);
    Texture ceiling;
    if (rng.chance(kWhiteCeilingChance)) {
        ceiling.colorA = ceiling.colorB = hsvToLinear(rng.uniform(), 0.1, rng.uniform(0.75, 0.95));
    } else {
        ceiling = randomTexture(rng);
    }
    const Texture floor = rng.chance(0.6) ? woodTexture(rng) : randomTexture(rng);
    // Box faces: 0 x-, 1 x+, 2 y- (ceiling: y is down), 3 y+ (floor), 4 z-, 5 z+.
    shell.faceTextures = {walls, walls, ceiling, floor, walls, walls};
    scene.primitives.push_back(shell);
    scene.roomIndex = 0;

    // Windows: 1-3, on walls, not overlapping each other.
    const int windowCount = rng.integer(1, 3);
    std::vector<std::pair<int, std::pair<double, double>>> usedSpans;  // face, [lo, hi]
    for (int w = 0, tries = 0; w < windowCount && tries < 50; ++tries) {
        const int face = std::vector<int>{0, 1, 4, 5}[rng.integer(0, 3)];
        const double length = wallLength(room, face);
        const double halfWidth = rng.uniform(0.4, std::min(1.0, length / 2 - 0.3));
        const double along =
            rng.uniform(-length / 2 + halfWidth + 0.2, length / 2 - halfWidth - 0.2);
        bool clash = false;
        for (const auto& [f, span] : usedSpans)
            clash |= f == face && along + halfWidth > span.first - 0.2 &&
                     along - halfWidth < span.second + 0.2;
        if (clash) continue;
        usedSpans.push_back({face, {along - halfWidth, along + halfWidth}});
        const double halfHeight = rng.uniform(0.4, std::min(0.8, (room.height - 1.1) / 2));
        const double sill = rng.uniform(0.7, std::max(0.71, room.height - 2 * halfHeight - 0.2));
        Primitive q = wallQuad(room, face, along, halfWidth, -(sill + halfHeight), halfHeight);
        q.label = "window";
        ++w;
        if (rng.chance(kBrightPanelWindowChance)) {
            // Frosted glass or a light box: a bright uniform panel, white to slightly cool.
            q.emission = Emission::Constant;
            q.radiance = Vec3d(0.9, 0.95, 1.0) *
                         rng.uniform(kWindowPanelRadiance[0], kWindowPanelRadiance[1]);
            scene.primitives.push_back(q);
            continue;
        }
        q.emission = Emission::Window;
        q.window = int(scene.windows.size());
        scene.primitives.push_back(q);
        WindowView view;
        view.panorama = panoramas[rng.integer(0, int(panoramas.size()) - 1)];
        view.yaw = rng.uniform(0, 2 * M_PI);
        view.scale = rng.uniform(kPanoramaScale[0], kPanoramaScale[1]);
        view.viewCentre = shell.centre;
        scene.windows.push_back(view);
    }

    // Furniture on the floor: 3-10 boxes, cylinders and spheres, apart from each other.
    std::vector<Footprint> placed;
    const int furniture = rng.integer(3, 10);
    for (int i = 0, tries = 0; i < furniture && tries < 200; ++tries) {
        Primitive p;
        const int kind = rng.integer(0, 9);  // 60% boxes, 25% cylinders, 15% spheres
        if (kind < 6) {
            p.shape = Shape::Box;
            p.half = Vec3d(rng.uniform(0.2, 0.9), rng.uniform(0.2, 0.6), rng.uniform(0.2, 0.6));
            p.rotation = rotationY(rng.uniform(0, M_PI));
            p.label = "box";
        } else if (kind < 9) {
            p.shape = Shape::Cylinder;
            p.half = Vec3d(rng.uniform(0.12, 0.4), rng.uniform(0.2, 0.55), 0);
            p.label = "cylinder";
        } else {
            p.shape = Shape::Sphere;
            p.half = Vec3d(rng.uniform(0.12, 0.4), 0, 0);
            p.label = "sphere";
        }
        const double footprint =
            p.shape == Shape::Box ? std::hypot(p.half.x(), p.half.z()) : p.half.x();
        const double height = p.shape == Shape::Sphere ? p.half.x() : p.half.y();
        if (2 * footprint + 0.2 > std::min(room.width, room.depth)) continue;
        const Footprint f{
            rng.uniform(-room.width / 2 + footprint + 0.05, room.width / 2 - footprint - 0.05),
            rng.uniform(-room.depth / 2 + footprint + 0.05, room.depth / 2 - footprint - 0.05),
            footprint};
        if (overlaps(placed, f)) continue;
        placed.push_back(f);
        p.centre = Vec3d(f.x, -height, f.z);
        p.texture = rng.chance(0.3) ? woodTexture(rng) : randomTexture(rng);
        randomMaterial(rng, p);
        scene.primitives.push_back(p);
        ++i;
    }

    // Ceiling lights: 1-3, each an emissive panel on the ceiling or a small sphere hanging
    // below it (visible to the camera when ahead of it), warm to neutral white. The Room
    // layout draws the same random numbers and then moves each light to its place on the
    // ceiling's middle line, keeping a shift of up to kLampLayoutJitter from where the random
    // layout put it (its random offset, scaled down), so that both layouts share every other
    // draw of the scene.
    const int lightCount = rng.integer(1, 3);
    const auto laidOut = roomLampCentres(room.width, room.depth, lightCount);
    const auto place = [&](int light, double randomX, double randomZ, double maxX, double maxZ) {
        if (lampLayout == LampLayout::Random) return std::make_pair(randomX, randomZ);
        const auto [x, z] = laidOut[light];
        return std::make_pair(std::clamp(x + kLampLayoutJitter * randomX / maxX, -maxX, maxX),
                              std::clamp(z + kLampLayoutJitter * randomZ / maxZ, -maxZ, maxZ));
    };
    for (int i = 0; i < lightCount; ++i) {
        const double warmth = rng.uniform(0, 1);
        const Vec3d white(1.0, 0.97 - 0.12 * warmth, 0.95 - 0.3 * warmth);
        if (rng.chance(0.5)) {
            const double hx = rng.uniform(0.15, 0.5), hz = rng.uniform(0.15, 0.5);
            const double maxX = room.width / 2 - hx - 0.2, maxZ = room.depth / 2 - hz - 0.2;
            // z before x: the order in which the compiler evaluated the arguments of the call
            // these draws were once made in, kept so that random layouts stay as they were.
            const double randomZ = rng.uniform(-maxZ, maxZ);
            const double randomX = rng.uniform(-maxX, maxX);
            const auto [x, z] = place(i, randomX, randomZ, maxX, maxZ);
            Primitive q = wallQuad(room, 2, x, hx, z, hz);
            q.emission = Emission::Constant;
            q.radiance = white * rng.uniform(kPanelRadiance[0], kPanelRadiance[1]);
            q.label = "panel";
            scene.primitives.push_back(q);
        } else {
            Primitive lamp;
            lamp.shape = Shape::Sphere;
            lamp.half = Vec3d(rng.uniform(0.05, 0.15), 0, 0);
            const double maxX = room.width / 2 - 0.5, maxZ = room.depth / 2 - 0.5;
            const double randomZ = rng.uniform(-maxZ, maxZ);  // in that order too
            const double drop = rng.uniform(0.3, 0.8);        // below the ceiling, m
            const double randomX = rng.uniform(-maxX, maxX);
            const auto [x, z] = place(i, randomX, randomZ, maxX, maxZ);
            lamp.centre = Vec3d(x, -room.height + drop, z);
            lamp.emission = Emission::Constant;
            lamp.radiance = white * rng.uniform(kLampRadiance[0], kLampRadiance[1]);
            lamp.label = "lamp";
            scene.primitives.push_back(lamp);
        }
    }

    // The reference camera: standing height (1.2-1.8 m), in the back half of the room along
    // its depth, away from the side walls, furniture and lamps, looking roughly down the
    // room's depth (yaw within +-35 degrees of it, either way along z) and roughly level.
    // Its pose defines the world frame.
    const bool facingMinusZ = rng.chance(0.5);
    Vec3d eye(0.0);
    for (int tries = 0; tries < 200; ++tries) {
        const double back = -room.depth / 2 + rng.uniform(0.5, 0.45 * room.depth);
        eye = Vec3d(rng.uniform(-0.35, 0.35) * room.width, -rng.uniform(1.2, 1.8),
                    facingMinusZ ? -back : back);
        if (scene.distanceToSolid(eye) > 0.5) break;
    }
    const double yaw =
        rng.uniform(-kCameraYawSpread, kCameraYawSpread) + (facingMinusZ ? M_PI : 0.0);
    const Mat3d camToRoom = rotationY(yaw) * rotationX(rng.uniform(-0.17, 0.09));
    const Mat3d roomToWorld = camToRoom.transpose();
    for (Primitive& p : scene.primitives) {
        p.centre = roomToWorld * (p.centre - eye);
        p.rotation = roomToWorld * p.rotation;
    }
    for (WindowView& w : scene.windows) {
        w.viewCentre = roomToWorld * (w.viewCentre - eye);
        w.roomToWorld = roomToWorld;
    }

    GeneratedScene out;
    out.scene = scene;
    PinholeCamera ref;
    ref.width = width;
    ref.height = height;
    const double fov = rng.uniform(50, 70) * M_PI / 180;  // horizontal field of view
    ref.fx = ref.fy = (width / 2.0) / std::tan(fov / 2);
    ref.cx = width / 2.0;
    ref.cy = height / 2.0;
    out.rig.ref = ref;
    out.rig.src = ref;
    out.rig.src.position = Vec3d(rng.uniform(0.05, 0.15), 0, 0);
    out.rig.tgt = ref;
    out.rig.tgt.position =
        Vec3d(rng.uniform(-0.15, 0.25), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.2));
    out.rig.tgt.rotation =
        rotationY(rng.uniform(-0.09, 0.09)) * rotationX(rng.uniform(-0.05, 0.05));
    return out;
}

}  // namespace lh::synth
