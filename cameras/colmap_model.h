// A COLMAP sparse model as COLMAP writes it: cameras, images (poses) and 3D points, read from
// the text files (cameras.txt, images.txt, points3D.txt) or the binary ones (.bin, little
// endian). Only what cameras.json needs is kept: intrinsics, poses, the 3D point ids each
// image observes and the points' positions (tracks and colours are skipped).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace lh {

struct ColmapCamera {
    std::uint32_t id = 0;
    std::string model;           // "PINHOLE", "SIMPLE_RADIAL", ... (COLMAP's names)
    std::uint64_t width = 0;     // pixels
    std::uint64_t height = 0;    // pixels
    std::vector<double> params;  // as COLMAP orders them for `model` (pixels, then unitless)
};

struct ColmapImage {
    std::uint32_t id = 0;
    // World-to-camera pose: x_cam = R(q) x_world + t. q = (qw, qx, qy, qz), Hamilton
    // convention; t in SfM units. Camera axes: +x right, +y down, +z forward.
    double q[4] = {1, 0, 0, 0};
    double t[3] = {0, 0, 0};
    std::uint32_t cameraId = 0;
    std::string name;                          // relative to COLMAP's image folder
    std::vector<std::int64_t> observedPoints;  // ids of the 3D points its keypoints see
};

struct ColmapModel {
    std::string dir;  // where it was read from, for messages
    std::map<std::uint32_t, ColmapCamera> cameras;
    std::map<std::uint32_t, ColmapImage> images;
    std::map<std::int64_t, std::array<double, 3>> points;  // id -> position (SfM units)
    bool hasPoints = false;  // false when the points file was not read
};

// Number of parameters of a COLMAP camera model, by id (binary files) or name (text); -1 when
// unknown. The binary cameras file cannot be parsed past a model whose count is unknown.
int colmapModelParamCount(int modelId);
int colmapModelParamCount(const std::string& modelName);
std::string colmapModelName(int modelId);  // "" when unknown

// Reads the model in `dir`. For each of the three files the binary one is used when present
// (COLMAP does the same), else the text one. `readPoints` false skips points3D entirely.
// Throws FileError naming the file for a missing, unreadable, truncated or malformed file.
ColmapModel readColmapModel(const std::string& dir, bool readPoints = true);

}  // namespace lh
