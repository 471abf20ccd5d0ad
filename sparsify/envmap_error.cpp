#include "sparsify/envmap_error.h"

#include "image/metrics.h"
#include "render/envmap.h"
#include "vdb/sparsity.h"
#include "vdb/volume_io.h"

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

namespace lh {

EnvmapSetError compareEnvmapSets(const std::vector<ImageRGB>& images,
                                 const std::vector<ImageRGB>& reference) {
    double squared = 0, mean = 0, psnrSum = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < images.size(); ++i) {
        for (std::size_t k = 0; k < images[i].pixels.size(); ++k) {
            squared += std::pow(double(images[i].pixels[k]) - reference[i].pixels[k], 2);
            mean += reference[i].pixels[k];
            ++n;
        }
        psnrSum += std::min(psnr(images[i], reference[i]), 100.0);
    }
    EnvmapSetError e;
    e.psnr = psnrSum / images.size();
    e.relativeRmse = mean > 0 ? std::sqrt(squared / n) / (mean / n) : 0.0;
    return e;
}

std::vector<ImageRGB> renderEnvmapsAt(const RenderVolume& volume, const std::vector<Vec3d>& points,
                                      int w, int h, double* msPerEnvmap,
                                      const MarchOptions& march) {
    std::vector<ImageRGB> images;
    const auto start = std::chrono::steady_clock::now();
    for (const Vec3d& p : points) images.push_back(renderEnvmap(volume, p, {w, h, march}));
    if (msPerEnvmap)
        *msPerEnvmap =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count() /
            std::max<std::size_t>(1, points.size());
    return images;
}

std::string scratchDirectory(const std::string& requested) {
    const std::filesystem::path dir =
        requested.empty() ? std::filesystem::temp_directory_path() /
                                ("lighthouse_sparsity_" + std::to_string(::getpid()))
                          : std::filesystem::path(requested);
    std::filesystem::create_directories(dir);
    return dir.string();
}

LightingVolume asStored(const LightingVolume& volume, bool half, const std::string& scratch,
                        uint64_t* bytes, int mantissaBits) {
    const std::string path =
        scratch + (half ? "/half" : "/float") + "_m" + std::to_string(mantissaBits) + ".vdb";
    saveSparseVolume(path, volume, half, mantissaBits);
    if (bytes) *bytes = std::filesystem::file_size(path);
    LightingVolume loaded = loadVolume(path);
    std::filesystem::remove(path);
    return loaded;
}

}  // namespace lh
