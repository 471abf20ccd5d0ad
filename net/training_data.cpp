#include "net/training_data.h"

#include "core/dataset_files.h"
#include "core/errors.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "net/observed_mask.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

namespace fs = std::filesystem;

namespace lh::net {

namespace {

// The reference view's z-depth, under the names the two data sets use.
constexpr const char* kDepthFiles[] = {dataset::kCyclesDepth, dataset::kDepth};

// One envmap's observed mask: the shipped env_K_mask.png, or one computed from the
// first-hit positions and the reference depth (read once per example, into `depth`).
std::vector<std::uint8_t> observedMask(const fs::path& dir, const EnvmapSample& sample,
                                       const ImageRGB& envmap, const PinholeCamera& reference,
                                       std::optional<ImageRGB>& depth) {
    const std::string stem = fs::path(sample.file).stem().string();
    const fs::path maskFile = dir / dataset::maskPng(stem);
    if (fs::is_regular_file(maskFile))
        return loadMask(maskFile.string(), envmap.width, envmap.height);

    const fs::path positionFile = dir / sample.positionFile;
    if (!depth)
        for (const char* name : kDepthFiles)
            if (fs::is_regular_file(dir / name)) {
                depth = readImage((dir / name).string());
                break;
            }
    if (sample.positionFile.empty() || !fs::is_regular_file(positionFile) || !depth)
        throw FileError("'" + dir.string() + "' has no " + maskFile.filename().string() +
                        ", nor the first-hit positions (cameras.json envmaps[].position_file) and "
                        "ref_depth.exr (or depth.exr) to compute the observed mask from");
    const ImageRGB positions = readImage(positionFile.string());
    if (positions.width != envmap.width || positions.height != envmap.height)
        throw InputError("'" + positionFile.string() + "' is " + std::to_string(positions.width) +
                         "x" + std::to_string(positions.height) + " but its envmap is " +
                         std::to_string(envmap.width) + "x" + std::to_string(envmap.height));
    try {
        return observedMaskFromDepth(positions, reference, *depth);
    } catch (const InputError& e) {
        throw InputError("'" + dir.string() + "': " + e.what());
    }
}

// The three photos of an example, each also rendered unclipped as VIEW.exr.
const char* const kPhotoViews[3] = {"ref", "src", "tgt"};

// How many of kPhotoViews (ref, src, tgt, in that order) `views` reads.
int viewCount(UnclippedViews views) { return views == UnclippedViews::RefAndSrc ? 2 : 3; }

}  // namespace

std::vector<std::string> listExamples(const std::string& dataDir) {
    if (!fs::is_directory(dataDir))
        throw FileError("data directory '" + dataDir +
                        "' not found (make one with 'lighthouse synth')");
    std::vector<std::string> out;
    for (const auto& entry : fs::directory_iterator(dataDir))
        // Hidden directories are examples still being written by `synth` (".ID.partial").
        if (entry.is_directory() && entry.path().filename().string().rfind('.', 0) != 0 &&
            fs::is_regular_file(entry.path() / dataset::kCameras))
            out.push_back(entry.path().string());
    std::sort(out.begin(), out.end());
    if (out.empty())
        throw FileError("'" + dataDir +
                        "' holds no examples (sub-directories with cameras.json); make some with "
                        "'lighthouse synth'");
    return out;
}

TrainingExample loadExample(const std::string& directory, bool withMasks) {
    const fs::path dir(directory);
    TrainingExample ex;
    ex.directory = directory;
    ex.cameras = loadCamerasFile((dir / dataset::kCameras).string());
    if (!ex.cameras.src || !ex.cameras.tgt || !ex.cameras.near || !ex.cameras.far)
        throw FileError("'" + (dir / dataset::kCameras).string() +
                        "' lacks src, tgt, near or far: not a training example");
    ex.ref = readImage((dir / dataset::viewPng("ref")).string());
    ex.src = readImage((dir / dataset::viewPng("src")).string());
    ex.tgt = readImage((dir / dataset::viewPng("tgt")).string());
    std::optional<ImageRGB> depth;  // read when the first mask must be computed
    for (const auto& e : ex.cameras.envmaps) {
        ex.envmaps.push_back(readImage((dir / e.file).string()));
        if (withMasks)
            ex.masks.push_back(observedMask(dir, e, ex.envmaps.back(), ex.cameras.ref, depth));
    }
    if (ex.envmaps.empty()) throw FileError("'" + directory + "' has no ground-truth envmaps");
    return ex;
}

std::string missingUnclippedView(const std::string& directory, UnclippedViews views) {
    for (int v = 0; v < viewCount(views); ++v)
        if (!fs::is_regular_file(fs::path(directory) / dataset::viewExr(kPhotoViews[v])))
            return dataset::viewExr(kPhotoViews[v]);
    return "";
}

bool useUnclippedViews(TrainingExample& ex, UnclippedViews views) {
    const fs::path dir(ex.directory);
    ImageRGB* images[3] = {&ex.ref, &ex.src, &ex.tgt};
    if (!missingUnclippedView(ex.directory, views).empty()) return false;
    const int count = viewCount(views);
    ImageRGB unclipped[3];
    for (int v = 0; v < count; ++v) {
        unclipped[v] = readImage((dir / dataset::viewExr(kPhotoViews[v])).string());
        if (unclipped[v].width != images[v]->width || unclipped[v].height != images[v]->height)
            return false;
        // A NaN would survive the clip and reach the network; the PNG is the safer photo.
        for (const float value : unclipped[v].pixels)
            if (std::isnan(value)) return false;
    }
    for (int v = 0; v < count; ++v) *images[v] = std::move(unclipped[v]);
    return true;
}

}  // namespace lh::net
