// A COLMAP model with a known answer, written by the tests in COLMAP's text and binary layouts
// (doc/format.rst and scripts/python/read_write_model.py of COLMAP; binary is little endian).
//
// The truth is set in the project's metric frame (reference camera = world, OpenCV axes); the
// model's world is that frame rotated by Q, scaled by s and shifted by T (x_w = s Q x + T), as
// structure from motion would arbitrarily choose it. A camera with cam_to_world (R, C) then has
// COLMAP's world-to-camera rotation R^T Q^T and translation -R^T Q^T T - s R^T C (camera
// coordinates scale with the world).
#pragma once

#include "cameras/colmap_model.h"
#include "core/vec.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace lh::test {

struct FixtureCamera {
    std::uint32_t id;
    std::string model;
    int modelId;
    std::uint64_t width, height;
    std::vector<double> params;
};

struct FixtureImage {
    std::uint32_t id;
    std::uint32_t cameraId;
    std::string name;
    Mat3d rotation;                    // true cam_to_world rotation, metric frame
    Vec3d centre;                      // true centre, metres
    std::vector<std::int64_t> points;  // 3D point ids its keypoints observe
};

struct FixturePoint {
    std::int64_t id;
    Vec3d position;  // metres, metric frame
};

struct ColmapFixture {
    std::vector<FixtureCamera> cameras;
    std::vector<FixtureImage> images;
    std::vector<FixturePoint> points;
    Mat3d worldRotation;  // Q
    double worldScale;    // s
    Vec3d worldShift;     // T
};

inline Mat3d axisAngle(Vec3d axis, double degrees) {
    axis.normalize();
    const double a = degrees * M_PI / 180.0, c = std::cos(a), s = std::sin(a), t = 1 - c;
    const double x = axis.x(), y = axis.y(), z = axis.z();
    return Mat3d(t * x * x + c, t * x * y - s * z, t * x * z + s * y,  //
                 t * x * y + s * z, t * y * y + c, t * y * z - s * x,  //
                 t * x * z - s * y, t * y * z + s * x, t * z * z + c);
}

// Unit quaternion (w, x, y, z) of a rotation matrix (Shepperd's method, stable for any angle).
inline void quaternionOf(const Mat3d& m, double q[4]) {
    const double tr = m(0, 0) + m(1, 1) + m(2, 2);
    if (tr > 0) {
        const double s = 2 * std::sqrt(1 + tr);
        q[0] = s / 4;
        q[1] = (m(2, 1) - m(1, 2)) / s;
        q[2] = (m(0, 2) - m(2, 0)) / s;
        q[3] = (m(1, 0) - m(0, 1)) / s;
    } else if (m(0, 0) > m(1, 1) && m(0, 0) > m(2, 2)) {
        const double s = 2 * std::sqrt(1 + m(0, 0) - m(1, 1) - m(2, 2));
        q[0] = (m(2, 1) - m(1, 2)) / s;
        q[1] = s / 4;
        q[2] = (m(0, 1) + m(1, 0)) / s;
        q[3] = (m(0, 2) + m(2, 0)) / s;
    } else if (m(1, 1) > m(2, 2)) {
        const double s = 2 * std::sqrt(1 + m(1, 1) - m(0, 0) - m(2, 2));
        q[0] = (m(0, 2) - m(2, 0)) / s;
        q[1] = (m(0, 1) + m(1, 0)) / s;
        q[2] = s / 4;
        q[3] = (m(1, 2) + m(2, 1)) / s;
    } else {
        const double s = 2 * std::sqrt(1 + m(2, 2) - m(0, 0) - m(1, 1));
        q[0] = (m(1, 0) - m(0, 1)) / s;
        q[1] = (m(0, 2) + m(2, 0)) / s;
        q[2] = (m(1, 2) + m(2, 1)) / s;
        q[3] = s / 4;
    }
}

// COLMAP's world-to-camera pose of a fixture image.
inline void colmapPose(const ColmapFixture& f, const FixtureImage& im, double q[4], double t[3]) {
    const Mat3d r = im.rotation.transpose() * f.worldRotation.transpose();
    const Vec3d tv = -(r * f.worldShift) - (im.rotation.transpose() * im.centre) * f.worldScale;
    quaternionOf(r, q);
    for (int i = 0; i < 3; ++i) t[i] = tv[i];
}

inline Vec3d colmapPoint(const ColmapFixture& f, const Vec3d& x) {
    return f.worldRotation * x * f.worldScale + f.worldShift;
}

// The standard case: ref (PINHOLE) at the origin, src (SIMPLE_PINHOLE) 0.12 m to the right,
// a little up and back, turned 4 degrees; a third, distorted (OPENCV) camera that is never
// asked for. 101 points seen by ref at depths 1.00, 1.04, ..., 5.00 m (1st percentile 1.04,
// 99th 4.96), one more seen only by src at 100 m, and one behind ref that ref "sees".
inline ColmapFixture standardFixture() {
    ColmapFixture f;
    f.cameras = {{1, "PINHOLE", 1, 640, 480, {500.5, 501.25, 320.3, 239.7}},
                 {2, "SIMPLE_PINHOLE", 0, 640, 480, {498.0, 321.0, 240.5}},
                 {7, "OPENCV", 4, 800, 600, {600, 600, 400, 300, 0.1, -0.02, 0.001, 0.002}}};
    FixtureImage ref{3, 1, "left/ref.jpg", Mat3d::identity(), Vec3d(0, 0, 0), {}};
    FixtureImage src{
        5, 2, "right/src.jpg", axisAngle(Vec3d(0.2, 1, 0.1), 4.0), Vec3d(0.12, -0.01, -0.015), {}};
    FixtureImage other{9, 7, "other.jpg", axisAngle(Vec3d(1, 0, 0), 10.0), Vec3d(-1, 0, 0), {}};
    for (int k = 0; k <= 100; ++k) {
        const double z = 1.0 + 0.04 * k;
        const Vec3d dir(std::sin(k * 0.7) * 0.4, std::cos(k * 1.3) * 0.3, 1.0);
        f.points.push_back({1000 + k, dir * z});  // depth along ref's +z is exactly z
        ref.points.push_back(1000 + k);
        src.points.push_back(1000 + k);
    }
    f.points.push_back({5000, Vec3d(0.1, 0.1, 100.0)});
    src.points.push_back(5000);
    f.points.push_back({5001, Vec3d(0.0, 0.0, -2.0)});
    ref.points.push_back(5001);
    f.images = {ref, src, other};
    f.worldRotation = axisAngle(Vec3d(0.3, -0.5, 0.8), 73.0);
    f.worldScale = 3.7;
    f.worldShift = Vec3d(2.5, -1.25, 7.0);
    return f;
}

inline void writeText(const ColmapFixture& f, const std::string& dir) {
    std::filesystem::create_directories(dir);
    std::ofstream cams(dir + "/cameras.txt"), ims(dir + "/images.txt"), pts(dir + "/points3D.txt");
    cams.precision(17);
    ims.precision(17);
    pts.precision(17);
    cams << "# Camera list with one line of data per camera:\n"
            "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n";
    for (const auto& c : f.cameras) {
        cams << c.id << " " << c.model << " " << c.width << " " << c.height;
        for (double p : c.params) cams << " " << p;
        cams << "\n";
    }
    ims << "# Image list with two lines of data per image:\n"
           "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
           "#   POINTS2D[] as (X, Y, POINT3D_ID)\n";
    for (const auto& im : f.images) {
        double q[4], t[3];
        colmapPose(f, im, q, t);
        ims << im.id << " " << q[0] << " " << q[1] << " " << q[2] << " " << q[3] << " " << t[0]
            << " " << t[1] << " " << t[2] << " " << im.cameraId << " " << im.name << "\n";
        // An unmatched keypoint (-1) first, then the observed points.
        ims << "10.5 20.5 -1";
        for (std::int64_t id : im.points) ims << " 100.25 200.75 " << id;
        ims << "\n";
    }
    pts << "# 3D point list with one line of data per point:\n"
           "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n";
    for (const auto& p : f.points) {
        const Vec3d x = colmapPoint(f, p.position);
        pts << p.id << " " << x.x() << " " << x.y() << " " << x.z() << " 128 64 32 0.5 3 1 5 1\n";
    }
}

template <class T>
void put(std::ofstream& out, T value) {
    out.write(reinterpret_cast<const char*>(&value), sizeof(T));  // the test host is little endian
}

inline void writeBinary(const ColmapFixture& f, const std::string& dir) {
    std::filesystem::create_directories(dir);
    std::ofstream cams(dir + "/cameras.bin", std::ios::binary);
    put<std::uint64_t>(cams, f.cameras.size());
    for (const auto& c : f.cameras) {
        put<std::int32_t>(cams, std::int32_t(c.id));
        put<std::int32_t>(cams, c.modelId);
        put<std::uint64_t>(cams, c.width);
        put<std::uint64_t>(cams, c.height);
        for (double p : c.params) put<double>(cams, p);
    }
    std::ofstream ims(dir + "/images.bin", std::ios::binary);
    put<std::uint64_t>(ims, f.images.size());
    for (const auto& im : f.images) {
        double q[4], t[3];
        colmapPose(f, im, q, t);
        put<std::int32_t>(ims, std::int32_t(im.id));
        for (double v : q) put<double>(ims, v);
        for (double v : t) put<double>(ims, v);
        put<std::int32_t>(ims, std::int32_t(im.cameraId));
        ims.write(im.name.c_str(), std::streamsize(im.name.size() + 1));  // with its '\0'
        put<std::uint64_t>(ims, im.points.size() + 1);
        put<double>(ims, 10.5);
        put<double>(ims, 20.5);
        put<std::int64_t>(ims, -1);
        for (std::int64_t id : im.points) {
            put<double>(ims, 100.25);
            put<double>(ims, 200.75);
            put<std::int64_t>(ims, id);
        }
    }
    std::ofstream pts(dir + "/points3D.bin", std::ios::binary);
    put<std::uint64_t>(pts, f.points.size());
    for (const auto& p : f.points) {
        const Vec3d x = colmapPoint(f, p.position);
        put<std::uint64_t>(pts, std::uint64_t(p.id));
        for (int i = 0; i < 3; ++i) put<double>(pts, x[i]);
        for (int i = 0; i < 3; ++i) put<std::uint8_t>(pts, 100);
        put<double>(pts, 0.5);  // reprojection error, pixels
        put<std::uint64_t>(pts, 2);
        for (std::int32_t v : {3, 1, 5, 1}) put<std::int32_t>(pts, v);
    }
}

}  // namespace lh::test
