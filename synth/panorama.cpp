#include "synth/panorama.h"

#include "core/errors.h"
#include "image/envmap_lookup.h"
#include "image/image_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace lh::synth {

Panorama::Panorama(const std::string& path) {
    const ImageRGB full = readImage(path);
    if (full.width != 2 * full.height)
        throw FileError("panorama '" + path + "' is " + std::to_string(full.width) + "x" +
                        std::to_string(full.height) + ", expected an equirectangular W = 2H image");
    int factor = 1;
    while (full.width / (factor * 2) >= 256) factor *= 2;
    image_ = ImageRGB(full.width / factor, full.height / factor);
    for (int y = 0; y < image_.height; ++y)
        for (int x = 0; x < image_.width; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0;
                for (int dy = 0; dy < factor; ++dy)
                    for (int dx = 0; dx < factor; ++dx) {
                        const float v = full.at(x * factor + dx, y * factor + dy)[c];
                        sum += std::isfinite(v) ? std::clamp(v, 0.f, kMaxPanoramaRadiance) : 0.f;
                    }
                image_.at(x, y)[c] = float(sum / (factor * factor));
            }
}

Vec3d Panorama::radiance(const Vec3d& direction) const { return sampleEnvmap(image_, direction); }

const Panorama& PanoramaLibrary::get(const std::string& name) {
    auto it = loaded_.find(name);
    if (it == loaded_.end())
        it = loaded_
                 .emplace(name, std::make_unique<Panorama>(
                                    (std::filesystem::path(folder_) / name).string()))
                 .first;
    return *it->second;
}

std::vector<std::string> PanoramaLibrary::names() const {
    std::vector<std::string> out;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(folder_, ec))
        if (entry.path().extension() == ".exr") out.push_back(entry.path().filename().string());
    if (ec || out.empty())
        throw FileError("no panoramas (*.exr) in '" + folder_ + "'; pass --hdri-dir");
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace lh::synth
