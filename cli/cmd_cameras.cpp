// `lighthouse cameras`: cameras.json for real photographs, from a COLMAP model (--colmap), from
// the photos' EXIF focal length for a rectified side-by-side pair (--exif), or by running COLMAP
// on the two photos (--photos). The file is what `predict`, `insert` and `render-view` read.
#include "cameras/colmap_convert.h"
#include "cameras/colmap_runner.h"
#include "cameras/exif_camera.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/errors.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

namespace lh::cli {

namespace {

namespace fs = std::filesystem;

struct CamerasOptions {
    std::string colmapDir;
    std::vector<std::string> exif;
    std::vector<std::string> photos;
    std::string ref, src;
    std::optional<double> baseline, near, far, fx;
    int minPoints = 20;
    std::string colmapExecutable = "colmap";
    bool keepWork = false;
    std::string output;
};

void printPair(const CamerasFile& c, const std::string& unit) {
    const PinholeCamera& s = *c.src;
    const Mat3d r = s.rotation;
    // Angle of the relative rotation, from its trace.
    const double cosAngle = std::max(-1.0, std::min(1.0, (r(0, 0) + r(1, 1) + r(2, 2) - 1) / 2));
    std::printf("ref: %dx%d, fx %.2f fy %.2f, cx %.2f cy %.2f (identity pose)\n", c.ref.width,
                c.ref.height, c.ref.fx, c.ref.fy, c.ref.cx, c.ref.cy);
    std::printf("src: %dx%d, fx %.2f fy %.2f, centre (%.4f, %.4f, %.4f) %s, rotated %.3f deg\n",
                s.width, s.height, s.fx, s.fy, s.position.x(), s.position.y(), s.position.z(),
                unit.c_str(), std::acos(cosAngle) * 180.0 / M_PI);
    if (c.near && c.far)
        std::printf("depth range: near %.4f .. far %.4f %s\n", *c.near, *c.far, unit.c_str());
    else
        std::printf("depth range: none (predict estimates it from the pair)\n");
}

void writeJson(AtomicOutput& out, const CamerasFile& cameras) {
    // Parsed back first: what is written is exactly what `predict` will accept.
    const std::string text = camerasToJson(cameras);
    parseCamerasJson(text, out.finalPath());
    std::ofstream f(out.tempPath());
    f << text << "\n";
    if (!f) throw FileError("cannot write '" + out.finalPath() + "'");
}

CamerasFile fromColmap(const ColmapModel& model, const CamerasOptions& o, const std::string& ref,
                       const std::string& src) {
    ColmapPairOptions p;
    p.ref = ref;
    p.src = src;
    p.baseline = o.baseline;
    p.near = o.near;
    p.far = o.far;
    p.minPoints = o.minPoints;
    const ColmapPairResult r = convertColmapPair(model, p);
    if (!r.metric)
        std::cerr << "warning: no --baseline: cameras.json keeps COLMAP's arbitrary units (the "
                     "ref-src distance is "
                  << r.sfmBaseline << "); give the distance between the cameras in metres\n";
    else
        std::printf("scale: %.6g m per COLMAP unit (COLMAP baseline %.6g)\n", r.scale,
                    r.sfmBaseline);
    if (r.depthPoints > 0)
        std::printf(
            "near/far from %d 3D points seen by the reference image (1st and 99th "
            "percentile of depth)\n",
            r.depthPoints);
    return r.cameras;
}

void checkOptions(const CamerasOptions& o) {
    const int modes = !o.colmapDir.empty() + !o.exif.empty() + !o.photos.empty();
    if (modes != 1) throw InputError("give exactly one of --colmap, --exif or --photos");
    if (!o.colmapDir.empty() && (o.ref.empty() || o.src.empty()))
        throw InputError("--colmap needs --ref and --src (image names as in images.txt)");
    if (o.colmapDir.empty() && (!o.ref.empty() || !o.src.empty()))
        throw InputError(
            "--ref and --src name images of a --colmap model; with --exif or "
            "--photos the first photo is the reference");
    if (!o.exif.empty() && !o.baseline)
        throw InputError("--exif needs --baseline (metres between the two cameras)");
    if (o.baseline) checkBaseline(*o.baseline);
    if (o.fx && !(std::isfinite(*o.fx) && *o.fx > 0))
        throw InputError("--fx must be a positive finite focal length in pixels");
    if (fileExtension(o.output) != ".json")
        throw InputError("output '" + o.output + "' must end in .json");
}

void warnOrientation(const std::string& path) {
    const ExifCameraInfo info = readExifCameraInfo(path);
    if (info.orientation != 1)
        std::cerr << "warning: '" << path << "' has EXIF orientation " << info.orientation
                  << ": its camera is for the upright photo, but predict reads the pixels as "
                     "stored; rotate the file first (exiftran -ai, or convert -auto-orient)\n";
}

void runCameras(const CamerasOptions& o) {
    checkOptions(o);
    AtomicOutput out(o.output);  // a bad output path fails before any work
    if (!o.colmapDir.empty()) {
        const bool needPoints = !(o.near && o.far);
        const CamerasFile c = fromColmap(readColmapModel(o.colmapDir, needPoints), o, o.ref, o.src);
        writeJson(out, c);
        printPair(c, o.baseline ? "m" : "COLMAP units");
    } else if (!o.exif.empty()) {
        ExifPairOptions p;
        p.baseline = *o.baseline;
        p.fx = o.fx;
        p.near = o.near;
        p.far = o.far;
        std::string report;
        const CamerasFile c = exifStereoPair(o.exif[0], o.exif[1], p, &report);
        for (const std::string& photo : o.exif) warnOrientation(photo);
        std::cout << report;
        writeJson(out, c);
        printPair(c, "m");
    } else {
        ColmapRunOptions run;
        run.executable = o.colmapExecutable;
        run.fx = o.fx;
        const ColmapRunResult r = runColmapOnPair(o.photos[0], o.photos[1], run);
        std::printf("colmap work folder: %s\n", r.workDir.c_str());
        const CamerasFile c =
            fromColmap(readColmapModel(r.modelDir, !(o.near && o.far)), o, r.refName, r.srcName);
        // The cameras describe the undistorted photos: they are written beside the output.
        const fs::path base = fs::path(o.output).replace_extension("");
        AtomicOutput refOut(base.string() + "_ref" + fileExtension(r.refImage));
        AtomicOutput srcOut(base.string() + "_src" + fileExtension(r.srcImage));
        fs::copy_file(r.refImage, refOut.tempPath(), fs::copy_options::overwrite_existing);
        fs::copy_file(r.srcImage, srcOut.tempPath(), fs::copy_options::overwrite_existing);
        writeJson(out, c);
        refOut.commit();
        srcOut.commit();
        std::printf("undistorted photos (use these with predict): %s %s\n",
                    refOut.finalPath().c_str(), srcOut.finalPath().c_str());
        printPair(c, o.baseline ? "m" : "COLMAP units");
        if (!o.keepWork) {
            std::error_code ec;
            fs::remove_all(r.workDir, ec);
        }
    }
    out.commit();
    std::printf("cameras -> %s\n", o.output.c_str());
}

}  // namespace

void addCamerasCommand(CLI::App& app) {
    auto o = std::make_shared<CamerasOptions>();
    CLI::App* cmd = app.add_subcommand(
        "cameras",
        "Write cameras.json for real photos: from a COLMAP model (--colmap DIR --ref NAME --src "
        "NAME), from EXIF for a rectified side-by-side pair (--exif A B), or by running colmap "
        "on two photos (--photos A B). The reference camera becomes the world frame (OpenCV "
        "axes: +x right, +y down, +z forward)");
    cmd->add_option("--colmap", o->colmapDir,
                    "COLMAP model folder (cameras, images, points3D as .txt or .bin); PINHOLE or "
                    "SIMPLE_PINHOLE cameras, i.e. after colmap image_undistorter");
    cmd->add_option("--ref", o->ref, "With --colmap: the reference image's name in the model");
    cmd->add_option("--src", o->src, "With --colmap: the source image's name in the model");
    cmd->add_option("--exif", o->exif,
                    "Rectified pair REF SRC: fx from EXIF, principal point at "
                    "the centre, SRC --baseline to the right of REF")
        ->expected(2);
    cmd->add_option("--photos", o->photos,
                    "Two photos REF SRC given to colmap (optional program: apt-get install "
                    "colmap); writes the undistorted photos beside the output")
        ->expected(2);
    cmd->add_option("--baseline", o->baseline,
                    "Distance between the two camera centres in metres (scales COLMAP's "
                    "arbitrary units; required with --exif)");
    cmd->add_option("--near", o->near,
                    "Nearest depth (m); default: from the 3D points, or none "
                    "with --exif (predict then estimates it)");
    cmd->add_option("--far", o->far, "Farthest depth (m); default as --near");
    cmd->add_option("--fx", o->fx, "Focal length in pixels (--exif, --photos), instead of EXIF");
    cmd->add_option("--min-points", o->minPoints,
                    "Fewest 3D points seen by the reference image for near/far")
        ->capture_default_str()
        ->check(CLI::Range(2, 1000000));
    cmd->add_option("--colmap-bin", o->colmapExecutable, "The colmap program (--photos)")
        ->capture_default_str();
    cmd->add_flag("--keep-work", o->keepWork, "Keep colmap's temporary work folder (--photos)");
    cmd->add_option("-o,--output", o->output, "Output cameras.json")->required();
    cmd->callback([o] { runCameras(*o); });
}

}  // namespace lh::cli
