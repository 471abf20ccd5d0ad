#include "vdb/example_volume.h"

#include <cmath>

namespace lh {

namespace {

struct Box {
    Vec3d lo, hi;
    bool contains(const Vec3d& p) const {
        return p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y() &&
               p.z() >= lo.z() && p.z() <= hi.z();
    }
};

// Room interior (metres). y is down: the ceiling is at y = -1.2, the floor at y = +1.5.
const Box kInterior{Vec3d(-2.5, -1.2, -1.5), Vec3d(2.5, 1.5, 6.0)};
constexpr double kWall = 0.25;      // wall thickness, metres
constexpr float kWallSigma = 40.f;  // per metre: a wall is opaque (exp(-10) over 0.25 m)

const Box kWindow{Vec3d(2.5, -0.6, 1.5), Vec3d(2.5 + kWall, 0.6, 3.5)};  // in the +x wall
const Box kLamp{Vec3d(-0.6, -1.2 - kWall, 2.0), Vec3d(0.6, -1.2, 3.0)};  // in the ceiling
const Box kTableTop{Vec3d(-0.7, 0.70, 2.6), Vec3d(0.7, 0.78, 3.6)};
const Box kTableLeg{Vec3d(-0.05, 0.78, 3.05), Vec3d(0.05, 1.5, 3.15)};
// Small objects near the camera, so that the finest levels hold content too.
const Box kCube{Vec3d(-0.65, 0.35, 1.2), Vec3d(-0.40, 0.60, 1.45)};  // in level 3
const Vec3d kBallCentre(0.22, 0.22, 0.62);                           // in level 4
constexpr double kBallRadius = 0.10;

MediumSample solid(float r, float g, float b, float sigma = kWallSigma) {
    return {sigma, openvdb::Vec3s(r, g, b)};
}

}  // namespace

MediumSample exampleRoomMedium(const Vec3d& p) {
    if (kWindow.contains(p)) return solid(2.0f, 3.0f, 5.0f);  // bright sky seen through glass
    if (kLamp.contains(p)) return solid(12.0f, 10.0f, 7.0f);  // warm emissive panel
    if (kTableTop.contains(p) || kTableLeg.contains(p)) return solid(0.60f, 0.30f, 0.08f);
    if (kCube.contains(p)) return solid(0.10f, 0.30f, 0.60f);                       // blue cube
    if ((p - kBallCentre).length() <= kBallRadius) return solid(0.9f, 0.8f, 0.2f);  // yellow ball
    const Box outer{kInterior.lo - Vec3d(kWall), kInterior.hi + Vec3d(kWall)};
    if (!outer.contains(p) || kInterior.contains(p)) return {};  // air (and outside the room)
    // Inside the shell: which wall? Nearest interior face wins.
    if (p.x() < kInterior.lo.x()) return solid(0.55f, 0.10f, 0.08f);  // red, -x
    if (p.x() > kInterior.hi.x()) return solid(0.10f, 0.45f, 0.12f);  // green, +x
    if (p.y() < kInterior.lo.y()) return solid(0.70f, 0.70f, 0.68f);  // ceiling
    if (p.y() > kInterior.hi.y()) {                                   // checkered wooden floor
        const bool odd = (int(std::floor(p.x() / 0.5)) + int(std::floor(p.z() / 0.5))) & 1;
        return odd ? solid(0.40f, 0.25f, 0.12f) : solid(0.28f, 0.17f, 0.08f);
    }
    if (p.z() > kInterior.hi.z()) return solid(0.45f, 0.45f, 0.45f);  // back wall ahead, +z
    return solid(0.15f, 0.20f, 0.35f);                                // blue wall behind, -z
}

LightingVolume makeExampleVolume(int levels, int resolution) {
    LightingVolume volume =
        LightingVolume::fromLayout(VolumeLayout::fromFarDepth(7.0, levels, resolution));
    for (int k = 0; k < levels; ++k) {
        const double h = volume.layout->voxelSize(k) / 4;  // sub-sample offset: 2x2x2 per voxel
        volume.fillLevel(k, [h](const Vec3d& centre) {
            double sigma = 0;
            Vec3d emission(0.0);  // sigma * colour, averaged: premultiplied box filter
            for (int s = 0; s < 8; ++s) {
                Vec3d p = centre + Vec3d((s & 1) ? h : -h, (s & 2) ? h : -h, (s & 4) ? h : -h);
                MediumSample m = exampleRoomMedium(p);
                sigma += m.sigma;
                emission += Vec3d(m.color.x(), m.color.y(), m.color.z()) * double(m.sigma);
            }
            if (sigma <= 0) return MediumSample{};
            const Vec3d color = emission / sigma;
            return MediumSample{float(sigma / 8), openvdb::Vec3s(float(color.x()), float(color.y()),
                                                                 float(color.z()))};
        });
    }
    volume.refCamera = exampleCameras().ref;
    return volume;
}

CamerasFile exampleCameras() {
    CamerasFile cams;
    PinholeCamera ref;
    ref.width = 320;
    ref.height = 240;
    ref.fx = ref.fy = 160.0 / std::tan(M_PI / 6);  // 60 degrees horizontal field of view
    ref.cx = 160.0;
    ref.cy = 120.0;
    cams.ref = ref;
    PinholeCamera src = ref;
    src.position = Vec3d(0.1, 0.0, 0.0);
    cams.src = src;
    cams.near = 1.0;
    cams.far = 7.0;
    return cams;
}

}  // namespace lh
