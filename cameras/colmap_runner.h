// Runs COLMAP (an optional program: Debian's `colmap` package) on two photos: feature
// extraction, exhaustive matching, the incremental mapper set up for two views, and
// undistortion to a PINHOLE model. The result is a model that convertColmapPair reads, and the
// undistorted photos the cameras describe.
#pragma once

#include <optional>
#include <string>

namespace lh {

struct ColmapRunOptions {
    std::string executable = "colmap";  // looked up on PATH when it has no '/'
    // Focal length in pixels; when known it is held fixed, since two views constrain it badly
    // (left free, it came out over 5 times too long on the bundled demo pair).
    // Without it, the photos' EXIF focal length is used when they have one.
    std::optional<double> fx;
};

struct ColmapRunResult {
    std::string workDir;   // temporary folder holding everything (the caller removes it;
                           // it is kept when a step fails, for its logs)
    std::string modelDir;  // the undistorted model (binary files)
    std::string refName;   // image names in that model
    std::string srcName;
    std::string refImage;  // the undistorted photos, as the model's cameras describe them
    std::string srcImage;
};

// Full path of `name` found on PATH (or `name` itself when it holds a '/' and is executable);
// empty when not found.
std::string findExecutable(const std::string& name);

// Runs the pipeline in a new temporary folder. Throws InputError when colmap is missing, and
// Error naming the step, its exit status, the last line of its log and the kept work folder
// when a step fails or the two photos could not be related.
ColmapRunResult runColmapOnPair(const std::string& refPhoto, const std::string& srcPhoto,
                                const ColmapRunOptions& options);

}  // namespace lh
