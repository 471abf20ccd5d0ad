// Pinhole cameras and the cameras.json file (docs/conventions.md#cameras: OpenCV axes, +x right, +y
// down, +z forward; pixel (u, v) has its centre at (u + 0.5, v + 0.5); pose = cam_to_world).
#pragma once

#include "core/vec.h"

#include <optional>
#include <string>
#include <vector>

namespace lh {

// A point this close to the camera plane (scene units), or behind it, is not in the image.
inline constexpr double kMinImageDepth = 1e-6;

struct PinholeCamera {
    int width = 0;                          // pixels
    int height = 0;                         // pixels
    double fx = 0, fy = 0, cx = 0, cy = 0;  // pixels
    Mat3d rotation = Mat3d::identity();     // camera -> world rotation (columns = camera axes)
    Vec3d position{0.0, 0.0, 0.0};          // camera centre in world units

    // Direction (unit length, world frame) through continuous pixel coordinates (px, py);
    // pixel centres are at integer + 0.5.
    Vec3d pixelDirection(double px, double py) const;
    // World point -> camera frame (z = depth along the optical axis).
    Vec3d worldToCamera(const Vec3d& world) const;
    // Camera frame -> continuous pixel coordinates (x, y); z must be > 0.
    Vec3d cameraToPixel(const Vec3d& cam) const;
    // A world point as the image shows it: continuous pixel coordinates (x, y) and depth z,
    // when the point lies in front of the camera (z > kMinImageDepth) and projects inside the
    // image (pixel (u, v) covers [u, u + 1) x [v, v + 1)); nothing otherwise, NaN included.
    std::optional<Vec3d> projectIntoImage(const Vec3d& world) const;

    // The same camera for the image resized to width x height: intrinsics scaled per axis, so
    // a world point lands at its old pixel coordinates times (width / old width, height / old
    // height).
    PinholeCamera resized(int newWidth, int newHeight) const;

    // Throws InputError naming `what` if the intrinsics or pose are impossible
    // (non-positive size or focal length, non-finite values, rotation not orthonormal with
    // determinant +1 within 1e-4).
    void validate(const std::string& what) const;
};

struct EnvmapSample {
    Vec3d position;
    std::string file;
    std::string positionFile;
};

struct CamerasFile {
    PinholeCamera ref;
    std::optional<PinholeCamera> src;
    std::optional<PinholeCamera> tgt;
    std::optional<double> near;  // scene units
    std::optional<double> far;   // scene units
    std::vector<EnvmapSample> envmaps;

    const PinholeCamera& view(const std::string& name) const;  // "ref", "src", "tgt"
};

// Parses and validates cameras.json. Throws FileError (unreadable, not JSON) or InputError
// (missing keys, impossible cameras, near >= far), each naming the file.
CamerasFile loadCamerasFile(const std::string& path);
CamerasFile parseCamerasJson(const std::string& text, const std::string& sourceName);
std::string camerasToJson(const CamerasFile& cameras);

// One camera as a JSON object string / parsed back (used for VDB metadata).
std::string cameraToJson(const PinholeCamera& camera);
PinholeCamera cameraFromJson(const std::string& text, const std::string& sourceName);

}  // namespace lh
