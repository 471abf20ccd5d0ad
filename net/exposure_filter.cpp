#include "net/exposure_filter.h"

#include "core/camera.h"
#include "core/dataset_files.h"
#include "image/image_io.h"

#include <filesystem>

namespace fs = std::filesystem;

namespace lh::net {

double clippedFraction(const ImageRGB& envmap) {
    const std::size_t pixels = std::size_t(envmap.width) * envmap.height;
    if (pixels == 0) return 0.0;
    std::size_t clipped = 0;
    for (std::size_t p = 0; p < pixels; ++p) {
        const float* v = &envmap.pixels[3 * p];
        clipped += (double(v[0]) + v[1] + v[2]) / 3.0 > 1.0;
    }
    return double(clipped) / double(pixels);
}

std::vector<std::string> withoutOverexposedScenes(const std::vector<std::string>& directories,
                                                  double maxClipped, std::ostream& progress) {
    std::vector<std::string> kept;
    for (std::size_t i = 0; i < directories.size(); ++i) {
        const fs::path dir(directories[i]);
        const CamerasFile cameras = loadCamerasFile((dir / dataset::kCameras).string());
        bool overexposed = false;
        for (const auto& e : cameras.envmaps)
            if (clippedFraction(readImage((dir / e.file).string())) > maxClipped) {
                overexposed = true;
                break;
            }
        if (!overexposed) kept.push_back(directories[i]);
        if ((i + 1) % 500 == 0 || i + 1 == directories.size())
            progress << "train: checked the exposure of " << i + 1 << "/" << directories.size()
                     << " scenes, " << kept.size() << " kept\n";
    }
    return kept;
}

}  // namespace lh::net
