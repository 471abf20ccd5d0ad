#include "vdb/volume_edit.h"

#include "core/errors.h"

#include <openvdb/tools/ValueTransformer.h>

#include <algorithm>
#include <cmath>

namespace lh {

namespace {

// Index box of a level's voxels whose centres may lie in a world box (over-approximated for
// rotated transforms: the callers test each centre).
openvdb::CoordBBox candidateVoxels(const VolumeLevel& level, const WorldBox& box) {
    openvdb::Vec3d lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (int c = 0; c < 8; ++c) {
        const Vec3d corner((c & 1) ? box.max.x() : box.min.x(), (c & 2) ? box.max.y() : box.min.y(),
                           (c & 4) ? box.max.z() : box.min.z());
        const Vec3d q = level.transform().worldToIndex(corner);
        lo = openvdb::math::minComponent(lo, q);
        hi = openvdb::math::maxComponent(hi, q);
    }
    openvdb::CoordBBox bbox(openvdb::Coord::floor(lo), openvdb::Coord::ceil(hi));
    bbox.intersect(level.domain);
    return bbox;
}

void checkBox(const WorldBox& box) {
    for (int a = 0; a < 3; ++a)
        if (!(box.min[a] < box.max[a]) || !std::isfinite(box.min[a]) || !std::isfinite(box.max[a]))
            throw InputError("a box needs finite corners with min < max on every axis");
}

// Returns how many voxels (over all levels) had their centre inside, i.e. were painted.
template <typename Inside>
std::size_t paint(LightingVolume& volume, const WorldBox& bounds, Inside inside, float sigma,
                  const openvdb::Vec3s& radiance) {
    std::size_t painted = 0;
    for (VolumeLevel& level : volume.levels) {
        auto density = level.density->getAccessor();
        auto color = level.color->getAccessor();
        const openvdb::CoordBBox bbox = candidateVoxels(level, bounds);
        for (auto it = bbox.begin(); it; ++it) {
            if (!inside(level.transform().indexToWorld(*it))) continue;
            ++painted;
            if (sigma > 0) {
                density.setValueOn(*it, sigma);
                color.setValueOn(*it, radiance);
            } else {
                density.setValueOff(*it, 0.f);
                color.setValueOff(*it, openvdb::Vec3s(0.f));
            }
        }
    }
    return painted;
}

void checkRadiance(const openvdb::Vec3s& radiance, float sigma) {
    for (int c = 0; c < 3; ++c)
        if (!(radiance[c] >= 0) || !std::isfinite(radiance[c]))
            throw InputError("radiance must be finite and >= 0");
    if (!(sigma > 0) || !std::isfinite(sigma)) throw InputError("density must be finite and > 0");
}

}  // namespace

std::size_t addEmissiveBox(LightingVolume& volume, const WorldBox& box,
                           const openvdb::Vec3s& radiance, float sigma) {
    checkBox(box);
    checkRadiance(radiance, sigma);
    return paint(
        volume, box, [&](const Vec3d& p) { return box.contains(p); }, sigma, radiance);
}

std::size_t addEmissiveSphere(LightingVolume& volume, const Vec3d& centre, double radius,
                              const openvdb::Vec3s& radiance, float sigma) {
    if (!(radius > 0) || !std::isfinite(radius)) throw InputError("sphere radius must be positive");
    checkRadiance(radiance, sigma);
    const WorldBox bounds{centre - Vec3d(radius), centre + Vec3d(radius)};
    return paint(
        volume, bounds, [&](const Vec3d& p) { return (p - centre).length() <= radius; }, sigma,
        radiance);
}

std::size_t eraseBox(LightingVolume& volume, const WorldBox& box) {
    checkBox(box);
    const std::size_t erased = paint(
        volume, box, [&](const Vec3d& p) { return box.contains(p); }, 0.f, openvdb::Vec3s(0.f));
    for (VolumeLevel& level : volume.levels) {
        level.density->pruneGrid();
        level.color->pruneGrid();
    }
    return erased;
}

void cropToBox(LightingVolume& volume, const WorldBox& box) {
    checkBox(box);
    std::vector<VolumeLevel> kept;
    for (VolumeLevel& level : volume.levels) {
        const openvdb::CoordBBox inside = candidateVoxels(level, box);
        if (inside.empty()) continue;  // the level lies wholly outside: drop it
        // Clip the trees to the box and shrink the domain with them.
        level.density->tree().clip(inside);
        level.color->tree().clip(inside);
        for (auto it = inside.begin(); it; ++it)
            if (!box.contains(level.transform().indexToWorld(*it))) {
                level.density->tree().setValueOff(*it, 0.f);
                level.color->tree().setValueOff(*it, openvdb::Vec3s(0.f));
            }
        level.domain = inside;
        kept.push_back(level);
    }
    if (kept.empty()) throw InputError("the crop box does not overlap the volume");
    volume.levels = kept;
    volume.layout.reset();  // no longer the nested layout
}

void scaleExposure(LightingVolume& volume, float factor) {
    if (!(factor >= 0) || !std::isfinite(factor))
        throw InputError("exposure factor must be finite and >= 0");
    for (VolumeLevel& level : volume.levels)
        openvdb::tools::foreach (level.color->beginValueAll(),
                                 [factor](const auto& it) { it.setValue(*it * factor); });
}

void scaleDensity(LightingVolume& volume, float factor) {
    if (!(factor >= 0) || !std::isfinite(factor))
        throw InputError("density factor must be finite and >= 0");
    for (VolumeLevel& level : volume.levels)
        openvdb::tools::foreach (level.density->beginValueAll(),
                                 [factor](const auto& it) { it.setValue(*it * factor); });
}

void clampValues(LightingVolume& volume, float maxDensity, float maxRadiance) {
    if (!(maxDensity > 0) || !(maxRadiance > 0)) throw InputError("clamp bounds must be positive");
    for (VolumeLevel& level : volume.levels) {
        openvdb::tools::foreach (level.density->beginValueAll(), [maxDensity](const auto& it) {
            it.setValue(std::min(*it, maxDensity));
        });
        openvdb::tools::foreach (level.color->beginValueAll(), [maxRadiance](const auto& it) {
            openvdb::Vec3s v = *it;
            for (int c = 0; c < 3; ++c) v[c] = std::min(v[c], maxRadiance);
            it.setValue(v);
        });
    }
}

}  // namespace lh
