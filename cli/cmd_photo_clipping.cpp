// `lighthouse photo-clipping DATA_DIR... [--max-photo-clipped F]`: how much of each data set's
// reference photos clips, and how bright the clipped pixels are in truth (image/photo_clipping.h),
// from the unclipped reference views (ref.exr). It compares a training set's photos with the
// photos the model will be given: a set whose clipped pixels are mostly walls teaches a network
// to leave clipped lamps dim.
#include "cli/commands.h"
#include "core/dataset_files.h"
#include "core/errors.h"
#include "image/image_io.h"
#include "image/photo_clipping.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace lh::cli {

namespace {

namespace fs = std::filesystem;

struct PhotoClippingOptions {
    std::vector<std::string> dataDirs;
    double maxPhotoClipped = 1.0;  // 1: the photos' own exposure
};

// DIR itself when it holds ref.exr, otherwise its example folders that do, sorted.
std::vector<fs::path> referenceViews(const std::string& dir) {
    const std::string name = dataset::viewExr("ref");
    if (!fs::is_directory(dir))
        throw FileError("'" + dir + "' is not a directory (give an example folder or a data set)");
    if (fs::is_regular_file(fs::path(dir) / name)) return {fs::path(dir) / name};
    std::vector<fs::path> out;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.is_directory() && fs::is_regular_file(entry.path() / name))
            out.push_back(entry.path() / name);
    std::sort(out.begin(), out.end());
    if (out.empty())
        throw FileError("no " + name + " in '" + dir +
                        "' or its folders: photo-clipping reads the unclipped reference views that "
                        "`lighthouse synth` writes (dev_cycles has them too)");
    return out;
}

// The value below which `fraction` of `sorted` (ascending, not empty) lies.
double quantile(const std::vector<double>& sorted, double fraction) {
    return sorted[std::size_t(fraction * double(sorted.size() - 1) + 0.5)];
}

void report(const std::string& dir, const PhotoClippingOptions& o) {
    const double white[3] = {1.0, 1.0, 1.0};
    std::vector<double> clipped, perPhoto;
    double pixels = 0;
    for (const fs::path& path : referenceViews(dir)) {
        const ImageRGB ref = readImage(path.string());
        const double exposure =
            o.maxPhotoClipped < 1.0
                ? std::min(1.0, exposureClippingAtMost(ref, white, o.maxPhotoClipped))
                : 1.0;
        const std::vector<double> here = clippedLuminances(ref, exposure);
        const double count = double(ref.pixels.size() / 3);
        pixels += count;
        perPhoto.push_back(count > 0 ? double(here.size()) / count : 0.0);
        clipped.insert(clipped.end(), here.begin(), here.end());
    }
    std::sort(perPhoto.begin(), perPhoto.end());
    std::printf(
        "%s: %zu reference photo%s%s; %.1f%% of their pixels clip (per photo: median "
        "%.1f%%, largest %.1f%%)\n",
        dir.c_str(), perPhoto.size(), perPhoto.size() == 1 ? "" : "s",
        o.maxPhotoClipped < 1.0 ? ", metered for their highlights" : "",
        100.0 * double(clipped.size()) / pixels, 100.0 * quantile(perPhoto, 0.5),
        100.0 * perPhoto.back());
    if (clipped.empty()) return;
    std::sort(clipped.begin(), clipped.end());
    double mean = 0;
    for (const double y : clipped) mean += y / double(clipped.size());
    const double bright = double(clipped.end() - std::upper_bound(clipped.begin(), clipped.end(),
                                                                  kLampBrightLuminance)) /
                          double(clipped.size());
    std::printf(
        "  true luminance of the clipped pixels: median %.2f, 90th percentile %.2f, mean "
        "%.2f; %.1f%% above %g (lamp or window bright)\n",
        quantile(clipped, 0.5), quantile(clipped, 0.9), mean, 100.0 * bright, kLampBrightLuminance);
}

}  // namespace

void addPhotoClippingCommand(CLI::App& app) {
    auto o = std::make_shared<PhotoClippingOptions>();
    CLI::App* cmd = app.add_subcommand(
        "photo-clipping",
        "How much of a data set's reference photos clips, and how bright the clipped pixels are "
        "in truth (from ref.exr): lamps and windows, or bright walls");
    cmd->add_option("data", o->dataDirs,
                    "Data sets (folders of examples, as synth writes them or as dev_cycles is) "
                    "or example folders; each is reported on its own")
        ->required();
    cmd->add_option("--max-photo-clipped", o->maxPhotoClipped,
                    "Meter each photo as `train --max-photo-clipped F` does: lower its exposure "
                    "until at most F of its pixels clip (1: the photos' own exposure)")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    cmd->callback([o] {
        for (const std::string& dir : o->dataDirs) report(dir, *o);
    });
}

}  // namespace lh::cli
