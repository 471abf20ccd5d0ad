// HDR panoramas seen through windows: loaded once, reduced, looked up by direction.
#pragma once

#include "core/vec.h"
#include "image/image.h"

#include <map>
#include <memory>
#include <string>

namespace lh::synth {

// Linear radiance above which a panorama is clipped: the sun in a CC0 sky reaches 3e4, which
// would make window lighting a noisy point light; 50 keeps bright skies bright but smooth.
constexpr float kMaxPanoramaRadiance = 50.f;

class Panorama {
public:
    // Reads an equirectangular EXR (docs/conventions.md#envmap-layout: row 0 up, centre column
    // forward), box-filters it down to at most 256 x 128 and clips it at kMaxPanoramaRadiance.
    explicit Panorama(const std::string& path);
    // Bilinear lookup along a unit direction in the panorama's own frame (y down).
    Vec3d radiance(const Vec3d& direction) const;
    const ImageRGB& image() const { return image_; }

private:
    ImageRGB image_;
};

// The panoramas of one folder, loaded on first use. Not thread-safe for loading: call
// get() for every name once before parallel work.
class PanoramaLibrary {
public:
    explicit PanoramaLibrary(std::string folder) : folder_(std::move(folder)) {}
    const Panorama& get(const std::string& name);
    std::vector<std::string> names() const;  // *.exr in the folder, sorted
    const std::string& folder() const { return folder_; }

private:
    std::string folder_;
    std::map<std::string, std::unique_ptr<Panorama>> loaded_;
};

}  // namespace lh::synth
