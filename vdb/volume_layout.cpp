#include "vdb/volume_layout.h"

#include "core/errors.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <sstream>

namespace lh {

namespace {
// Voxels over all levels above which we refuse a layout: a dense volume stores 4 floats per
// voxel, so 2^28 voxels is 4 GiB. Filling one level also holds it densely (16 bytes a voxel),
// hence the per-level resolution cap: 512^3 is 2 GiB.
constexpr double kMaxLayoutVoxels = 268435456.0;
constexpr int kMaxResolution = 512;
// Smallest voxel of a layout from the cameras, metres: a micrometre, far below any room's
// detail and far above what OpenVDB's transforms can invert.
constexpr double kMinVoxelSize = 1e-6;
}  // namespace

VolumeLayout VolumeLayout::fromFarDepth(double far, int levels, int resolution) {
    if (!(std::isfinite(far) && far > 0))
        throw InputError("far depth must be positive and finite, got " + std::to_string(far));
    VolumeLayout layout;
    layout.s0 = 2.0 * std::min(far, 20.0);
    layout.levels = levels;
    layout.resolution = resolution;
    layout.validate();
    // OpenVDB cannot invert the transform of voxels this small ("non-zero scale values
    // required"); a far depth this small is a mistake in the cameras, not a scene.
    if (layout.voxelSize(levels - 1) < kMinVoxelSize) {
        std::ostringstream why;
        why << "the cameras' far depth of " << far << " m gives voxels smaller than "
            << kMinVoxelSize
            << " m: near and far in cameras.json are depths in metres (e.g. 0.5 and 20)";
        throw InputError(why.str());
    }
    return layout;
}

double VolumeLayout::side(int level) const { return s0 / std::ldexp(1.0, level); }

double VolumeLayout::voxelSize(int level) const { return side(level) / resolution; }

WorldBox VolumeLayout::box(int level) const {
    const double s = side(level);
    if (level == 0) return {Vec3d(-s / 2, -s / 2, -s / 2), Vec3d(s / 2, s / 2, s / 2)};
    return {Vec3d(-s / 2, -s / 2, 0.0), Vec3d(s / 2, s / 2, s)};
}

openvdb::math::Transform::Ptr VolumeLayout::transform(int level) const {
    const double v = voxelSize(level);
    auto xform = openvdb::math::Transform::createLinearTransform(v);
    xform->postTranslate(box(level).min + Vec3d(v / 2));
    return xform;
}

void VolumeLayout::validate() const {
    if (!(std::isfinite(s0) && s0 > 0))
        throw InputError("layout: s0 must be positive and finite, got " + std::to_string(s0));
    if (levels < 1 || levels > 16)
        throw InputError("layout: level count must be in [1, 16], got " + std::to_string(levels));
    if (resolution < 2)
        throw InputError("layout: resolution must be at least 2, got " +
                         std::to_string(resolution));
    if (resolution > kMaxResolution)
        throw ResourceError("layout: resolution " + std::to_string(resolution) +
                            " would exhaust memory (at most " + std::to_string(kMaxResolution) +
                            " voxels per side)");
    const double voxels = double(levels) * std::pow(double(resolution), 3);
    if (voxels > kMaxLayoutVoxels)
        throw ResourceError("layout: " + std::to_string(levels) + " x " +
                            std::to_string(resolution) + "^3 voxels would exhaust memory (limit " +
                            std::to_string(int64_t(kMaxLayoutVoxels)) + " voxels)");
}

std::string VolumeLayout::toJson() const {
    return nlohmann::json{{"s0", s0}, {"levels", levels}, {"resolution", resolution}}.dump();
}

namespace {

// A whole number that fits an int (5 or 5.0; a program that rewrites the JSON may write
// either). json's get<int>() of 1e300 is undefined behaviour (a float-to-int conversion out of
// range, which UBSan caught on an export's manifest) and of 2^32 + 1 wraps to 1: both refused.
int wholeNumber(const nlohmann::json& j, const char* key, const std::string& sourceName) {
    const nlohmann::json& v = j.at(key);
    const double d = v.is_number() ? v.get<double>() : 0.5;
    if (!(std::floor(d) == d && d >= double(INT_MIN) && d <= double(INT_MAX)))
        throw FileError(sourceName + ": layout metadata '" + key + "' is not a whole number, got " +
                        v.dump());
    return int(d);
}

}  // namespace

VolumeLayout VolumeLayout::fromJson(const std::string& text, const std::string& sourceName) {
    try {
        auto j = nlohmann::json::parse(text);
        VolumeLayout layout;
        layout.s0 = j.at("s0").get<double>();
        layout.levels = wholeNumber(j, "levels", sourceName);
        layout.resolution = wholeNumber(j, "resolution", sourceName);
        layout.validate();
        return layout;
    } catch (const nlohmann::json::exception&) {
        throw FileError(sourceName + ": layout metadata is not valid");
    }
}

}  // namespace lh
