#include "cameras/colmap_runner.h"

#include "cameras/colmap_model.h"
#include "cameras/exif_camera.h"
#include "core/atomic_file.h"
#include "core/errors.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace lh {

namespace {

namespace fs = std::filesystem;

std::string lastLine(const std::string& path) {
    std::ifstream in(path);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    return last;
}

// Runs argv with stdout and stderr into `log`, stdin from /dev/null; returns the exit status
// (128 + signal when killed, 127 when it could not be started).
int runLogged(const std::vector<std::string>& argv, const std::string& log) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const pid_t pid = fork();
    if (pid < 0)
        throw Error(std::string("cannot start colmap: fork failed: ") + std::strerror(errno));
    if (pid == 0) {
        const int out = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int in = open("/dev/null", O_RDONLY);
        if (out < 0 || in < 0) _exit(127);
        dup2(in, 0);
        dup2(out, 1);
        dup2(out, 2);
        // COLMAP links Qt; without a display it must not try to open one.
        setenv("QT_QPA_PLATFORM", "offscreen", 0);
        execv(args[0], args.data());
        _exit(127);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return 127;
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
    return 127;
}

std::string number(double v) {
    std::ostringstream ss;
    ss.precision(10);
    ss << v;
    return ss.str();
}

}  // namespace

std::string findExecutable(const std::string& name) {
    auto executable = [](const fs::path& p) {
        std::error_code ec;
        return fs::is_regular_file(p, ec) && access(p.c_str(), X_OK) == 0;
    };
    if (name.find('/') != std::string::npos) return executable(name) ? name : "";
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "");
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        const fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
        if (executable(candidate)) return candidate.string();
    }
    return "";
}

ColmapRunResult runColmapOnPair(const std::string& refPhoto, const std::string& srcPhoto,
                                const ColmapRunOptions& o) {
    const std::string colmap = findExecutable(o.executable);
    if (colmap.empty())
        throw InputError("'" + o.executable +
                         "' not found: --photos needs COLMAP "
                         "(apt-get install colmap), or run it yourself and use --colmap");
    // Sizes (and EXIF focal lengths) first, so that unreadable photos fail before COLMAP runs.
    const ExifCameraInfo ri = readExifCameraInfo(refPhoto), si = readExifCameraInfo(srcPhoto);
    const bool sameSize = ri.storedWidth == si.storedWidth && ri.storedHeight == si.storedHeight;
    std::optional<double> fx = o.fx;
    if (!fx && sameSize) {
        try {
            fx = exifFocalPixels(ri, refPhoto);
        } catch (const InputError&) {
            // No EXIF focal length: COLMAP guesses one and refines it.
        }
    }

    std::string tmpl = (fs::temp_directory_path() / "lighthouse-colmap-XXXXXX").string();
    if (!mkdtemp(tmpl.data()))
        throw FileError("cannot create a temporary folder for colmap: " +
                        std::string(std::strerror(errno)));
    ColmapRunResult r;
    r.workDir = tmpl;
    const fs::path work(r.workDir);
    fs::create_directories(work / "images");
    fs::create_directories(work / "sparse");
    // Fixed names, so that two photos called the same in different folders stay apart.
    r.refName = "ref" + fileExtension(refPhoto);
    r.srcName = "src" + fileExtension(srcPhoto);
    fs::copy_file(refPhoto, work / "images" / r.refName);
    fs::copy_file(srcPhoto, work / "images" / r.srcName);

    const std::string db = (work / "database.db").string(), images = (work / "images").string();
    // Runs one colmap command; returns its exit status when `mayFail`, else throws on failure.
    auto step = [&](const std::string& name, std::vector<std::string> args, bool mayFail = false) {
        args.insert(args.begin(), {colmap, name});
        const std::string log = (work / (name + ".log")).string();
        const int status = runLogged(args, log);
        if (status != 0 && !mayFail)
            throw Error("colmap " + name + " failed (exit " + std::to_string(status) +
                        "): " + lastLine(log) + " [log: " + log + "]");
        return status;
    };
    std::vector<std::string> extract = {"--database_path",
                                        db,
                                        "--image_path",
                                        images,
                                        "--ImageReader.camera_model",
                                        "SIMPLE_RADIAL",
                                        "--SiftExtraction.use_gpu",
                                        "0",
                                        "--SiftExtraction.num_threads",
                                        "1"};
    if (sameSize) {
        // One camera for both photos (two shots of one lens, or a rectified pair).
        extract.insert(extract.end(), {"--ImageReader.single_camera", "1"});
        if (fx)
            extract.insert(extract.end(), {"--ImageReader.camera_params",
                                           number(*fx) + "," + number(0.5 * ri.storedWidth) + "," +
                                               number(0.5 * ri.storedHeight) + ",0"});
    }
    step("feature_extractor", extract);
    // One thread for extraction, matching and mapping: with several, RANSAC's random samples depend
    // on thread timing and the pose (and the near/far range) change from run to run; two photos
    // take a few seconds either way. The seed is COLMAP's default, written out.
    step("exhaustive_matcher", {"--database_path", db, "--SiftMatching.use_gpu", "0",
                                "--SiftMatching.num_threads", "1", "--random_seed", "0"});
    // The mapper's defaults are made for many views: it drops models of fewer than 10 images
    // and wants 16 degrees of triangulation angle to start; a stereo pair a hand's width
    // apart gives a degree or two.
    std::vector<std::string> map = {"--database_path",
                                    db,
                                    "--image_path",
                                    images,
                                    "--output_path",
                                    (work / "sparse").string(),
                                    "--Mapper.min_model_size",
                                    "2",
                                    "--Mapper.multiple_models",
                                    "0",
                                    "--Mapper.init_min_num_inliers",
                                    "30",
                                    "--Mapper.init_min_tri_angle",
                                    "0.5",
                                    "--Mapper.tri_min_angle",
                                    "0.5",
                                    "--Mapper.filter_min_tri_angle",
                                    "0.5",
                                    "--Mapper.num_threads",
                                    "1",
                                    "--random_seed",
                                    "0"};
    if (fx)
        map.insert(map.end(), {"--Mapper.ba_refine_focal_length", "0",
                               "--Mapper.ba_refine_extra_params", "0"});
    // The mapper fails ("failed to create sparse model") when it finds no initial pair; it
    // may also succeed with a model that holds one photo only. Both mean: no relative pose.
    const int mapped = step("mapper", map, true);
    const fs::path sparse = work / "sparse" / "0";
    std::error_code ec;
    bool related = mapped == 0 && fs::is_directory(sparse, ec);
    if (related) related = readColmapModel(sparse.string(), false).images.size() >= 2;
    if (!related) {
        const std::string log = (work / "mapper.log").string();
        throw Error(
            "colmap could not relate the two photos (no reconstruction holds both: too "
            "few matches; do they show the same scene?): " +
            lastLine(log) + " [log: " + log + "]");
    }
    step("image_undistorter",
         {"--image_path", images, "--input_path", sparse.string(), "--output_path",
          (work / "dense").string(), "--output_type", "COLMAP"});
    r.modelDir = (work / "dense" / "sparse").string();
    r.refImage = (work / "dense" / "images" / r.refName).string();
    r.srcImage = (work / "dense" / "images" / r.srcName).string();
    return r;
}

}  // namespace lh
