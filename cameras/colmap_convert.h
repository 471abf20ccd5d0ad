// A COLMAP model's two images -> cameras.json: poses re-expressed in the reference camera's
// frame (the project's world), scaled to a metric baseline, intrinsics kept, near/far from the
// 3D points the reference image sees.
//
// COLMAP's camera frame is the project's (OpenCV axes: +x right, +y down, +z forward) and both
// put pixel centres at integer + 0.5, so intrinsics and axes carry over unchanged; only the
// world frame (COLMAP's arbitrary SfM frame -> the reference camera) and the scale change.
#pragma once

#include "cameras/colmap_model.h"
#include "core/camera.h"

#include <optional>
#include <string>

namespace lh {

struct ColmapPairOptions {
    std::string ref;  // image names as in images.txt (a unique file name also matches)
    std::string src;
    // Metric distance between the two camera centres (metres, the project's scene unit).
    // Without it the SfM units are kept: the result is then only known up to scale.
    std::optional<double> baseline;
    // Depth range (scene units, after scaling); each one given replaces its estimate.
    std::optional<double> near, far;
    int minPoints = 20;            // fewer 3D points in front of ref -> no estimate
    double lowPercentile = 1.0;    // near = this percentile of the points' depths
    double highPercentile = 99.0;  // far = this one
};

struct ColmapPairResult {
    CamerasFile cameras;
    double scale = 1.0;        // scene units per SfM unit (1 without a baseline)
    double sfmBaseline = 0.0;  // ref-src distance in SfM units
    int depthPoints = 0;       // 3D points used for near/far (0 when both were given)
    bool metric = false;       // a baseline was given
};

// Rotation of the unit quaternion (qw, qx, qy, qz), Hamilton convention (COLMAP's, Eigen's).
// The quaternion is normalised first; throws InputError for a zero or non-finite one.
Mat3d rotationFromQuaternion(const double q[4]);

// Intrinsics of a PINHOLE or SIMPLE_PINHOLE camera, or of SIMPLE_RADIAL, RADIAL, OPENCV or
// FULL_OPENCV with every distortion parameter zero (pose left at identity). Any other camera
// throws InputError: distorted images need COLMAP's image_undistorter first.
PinholeCamera pinholeFromColmap(const ColmapCamera& camera, const std::string& imageName);

// Throws InputError for a baseline that is not a positive finite length.
void checkBaseline(double baseline);

// The conversion. Throws InputError for a name not in the model (listing some that are), the
// same image twice, an unsupported camera model, coincident camera centres, too few points for
// near/far, or near >= far.
ColmapPairResult convertColmapPair(const ColmapModel& model, const ColmapPairOptions& options);

}  // namespace lh
