#include "cameras/colmap_convert.h"

#include "core/errors.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace lh {

namespace {

std::string number(double v) {
    std::ostringstream ss;
    ss.precision(6);
    ss << v;
    return ss.str();
}

const ColmapImage& findImage(const ColmapModel& model, const std::string& name, const char* role) {
    // Exact name first (COLMAP names are relative to its image folder, e.g. "left/a.jpg"),
    // then a unique match on the file name alone, so "a.jpg" finds "left/a.jpg".
    for (const auto& [id, im] : model.images)
        if (im.name == name) return im;
    const std::string wanted = std::filesystem::path(name).filename().string();
    const ColmapImage* match = nullptr;
    int matches = 0;
    for (const auto& [id, im] : model.images)
        if (std::filesystem::path(im.name).filename().string() == wanted) {
            match = &im;
            ++matches;
        }
    if (matches == 1) return *match;
    std::string known;
    int listed = 0;
    for (const auto& [id, im] : model.images) {
        if (listed == 5) {
            known += ", ...";
            break;
        }
        known += (listed++ ? ", " : "") + im.name;
    }
    if (matches > 1)
        throw InputError(std::string("--") + role + " '" + name + "' matches " +
                         std::to_string(matches) + " images of the COLMAP model '" + model.dir +
                         "'; give the full name as in images.txt");
    throw InputError(std::string("--") + role + " image '" + name +
                     "' is not in the COLMAP model '" + model.dir + "' (" +
                     std::to_string(model.images.size()) +
                     " images: " + (known.empty() ? "none" : known) + ")");
}

// World-to-camera of a COLMAP image as a rotation and translation.
void worldToCamera(const ColmapImage& im, Mat3d& r, Vec3d& t) {
    r = rotationFromQuaternion(im.q);
    t = Vec3d(im.t[0], im.t[1], im.t[2]);
}

// Linear interpolation between order statistics (numpy's default), p in [0, 100].
double percentile(std::vector<double> v, double p) {
    std::sort(v.begin(), v.end());
    const double pos = p / 100.0 * double(v.size() - 1);
    const auto lo = std::size_t(std::floor(pos));
    const auto hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (pos - double(lo)) * (v[hi] - v[lo]);
}

}  // namespace

Mat3d rotationFromQuaternion(const double q[4]) {
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!std::isfinite(n) || n < 1e-12)
        throw InputError("COLMAP pose quaternion is zero or not finite");
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    return Mat3d(1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
                 2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                 2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y));
}

PinholeCamera pinholeFromColmap(const ColmapCamera& c, const std::string& imageName) {
    PinholeCamera cam;
    const std::string where =
        "image '" + imageName + "' (COLMAP camera " + std::to_string(c.id) + ", " + c.model + ")";
    if (c.width < 1 || c.height < 1 || c.width > 65536 || c.height > 65536)
        throw InputError(where + ": image size " + std::to_string(c.width) + "x" +
                         std::to_string(c.height) + " is not in [1, 65536]");
    cam.width = int(c.width);
    cam.height = int(c.height);
    // Models whose distortion parameters are all zero are pinholes too: image_undistorter
    // copies such a camera unchanged instead of rewriting it as PINHOLE.
    std::size_t focal = 0;  // 1: one focal length (f, cx, cy, ...), 2: two (fx, fy, cx, cy, ...)
    if (c.model == "SIMPLE_PINHOLE" || c.model == "SIMPLE_RADIAL" || c.model == "RADIAL")
        focal = 1;
    else if (c.model == "PINHOLE" || c.model == "OPENCV" || c.model == "FULL_OPENCV")
        focal = 2;
    bool undistorted = focal > 0 && c.params.size() >= focal + 2;
    for (std::size_t i = focal + 2; undistorted && i < c.params.size(); ++i)
        undistorted = c.params[i] == 0.0;
    if (!undistorted)
        throw InputError(where +
                         ": only PINHOLE and SIMPLE_PINHOLE cameras are supported; "
                         "undistort the images first (colmap image_undistorter --image_path "
                         "IMAGES --input_path MODEL --output_path OUT) and use OUT/sparse with "
                         "the images in OUT/images");
    cam.fx = c.params[0];
    cam.fy = c.params[focal - 1];
    cam.cx = c.params[focal];
    cam.cy = c.params[focal + 1];
    cam.validate(where);
    return cam;
}

void checkBaseline(double baseline) {
    if (!(std::isfinite(baseline) && baseline > 0))
        throw InputError("--baseline must be a positive finite distance in metres (got " +
                         number(baseline) + ")");
}

ColmapPairResult convertColmapPair(const ColmapModel& model, const ColmapPairOptions& o) {
    if (o.baseline) checkBaseline(*o.baseline);
    const ColmapImage& ref = findImage(model, o.ref, "ref");
    const ColmapImage& src = findImage(model, o.src, "src");
    if (ref.id == src.id)
        throw InputError("--ref and --src name the same image '" + ref.name + "' (zero baseline)");
    auto cameraOf = [&](const ColmapImage& im) -> const ColmapCamera& {
        const auto it = model.cameras.find(im.cameraId);
        if (it == model.cameras.end())
            throw InputError("image '" + im.name + "' uses camera " + std::to_string(im.cameraId) +
                             ", which is not in the COLMAP model '" + model.dir + "'");
        return it->second;
    };

    ColmapPairResult result;
    result.cameras.ref = pinholeFromColmap(cameraOf(ref), ref.name);
    PinholeCamera srcCam = pinholeFromColmap(cameraOf(src), src.name);

    // x_ref = Rr x_w + tr and x_src = Rs x_w + ts give x_src = Rs Rr^T (x_ref - tr) + ts, so in
    // the reference frame the source camera's cam_to_world is rotation Rr Rs^T and centre
    // Rr C_s + tr with C_s = -Rs^T ts its centre in COLMAP's world.
    Mat3d rr, rs;
    Vec3d tr, ts;
    worldToCamera(ref, rr, tr);
    worldToCamera(src, rs, ts);
    const Vec3d centreSrc = -(rs.transpose() * ts);
    const Vec3d position = rr * centreSrc + tr;
    result.sfmBaseline = position.length();
    if (!(result.sfmBaseline > 1e-9 * (1.0 + tr.length())))
        throw InputError("images '" + ref.name + "' and '" + src.name +
                         "' are at the same place in the COLMAP model (zero baseline)");
    result.metric = bool(o.baseline);
    result.scale = o.baseline ? *o.baseline / result.sfmBaseline : 1.0;
    srcCam.rotation = rr * rs.transpose();
    srcCam.position = position * result.scale;
    srcCam.validate("image '" + src.name + "' pose");
    result.cameras.src = srcCam;  // ref keeps the identity pose of a default PinholeCamera

    // near/far: percentiles of the depths (along the reference optical axis) of the 3D points
    // the reference image observes, in front of it.
    if (!(o.near && o.far)) {
        std::vector<double> depths;
        for (const std::int64_t id : ref.observedPoints) {
            const auto it = model.points.find(id);
            if (it == model.points.end()) continue;
            const Vec3d x(it->second[0], it->second[1], it->second[2]);
            const double z = (rr * x + tr).z();
            if (z > 0) depths.push_back(z * result.scale);
        }
        if (int(depths.size()) < o.minPoints)
            throw InputError("only " + std::to_string(depths.size()) +
                             " 3D points of the COLMAP model are seen in front of '" + ref.name +
                             "' (near/far need " + std::to_string(o.minPoints) +
                             "); give --near and --far");
        result.depthPoints = int(depths.size());
        if (!o.near) result.cameras.near = percentile(depths, o.lowPercentile);
        if (!o.far) result.cameras.far = percentile(depths, o.highPercentile);
    }
    if (o.near) result.cameras.near = *o.near;
    if (o.far) result.cameras.far = *o.far;
    const double n = *result.cameras.near, f = *result.cameras.far;
    if (!(std::isfinite(n) && n > 0 && std::isfinite(f) && n < f))
        throw InputError("depth range near " + number(n) + " .. far " + number(f) +
                         " is not 0 < near < far");
    return result;
}

}  // namespace lh
