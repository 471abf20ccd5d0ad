#include "vdb/lighting_volume.h"

#include "core/errors.h"

#include <openvdb/tools/Dense.h>

#include <algorithm>
#include <cmath>

namespace lh {

std::string gridKind(const openvdb::GridBase& grid) {
    if (grid.isType<openvdb::FloatGrid>()) return "a FloatGrid";
    if (grid.isType<openvdb::Vec3SGrid>()) return "a Vec3SGrid";
    return "a " + grid.valueType() + " grid";
}

std::string densityGridName(int level) { return "density_L" + std::to_string(level); }
std::string colorGridName(int level) { return "color_L" + std::to_string(level); }

WorldBox VolumeLevel::worldBounds() const {
    const auto& xf = transform();
    const Vec3d lo = domain.min().asVec3d() - Vec3d(0.5), hi = domain.max().asVec3d() + Vec3d(0.5);
    WorldBox box{Vec3d(std::numeric_limits<double>::max()),
                 Vec3d(-std::numeric_limits<double>::max())};
    for (int c = 0; c < 8; ++c) {
        Vec3d corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(),
                     (c & 4) ? hi.z() : lo.z());
        Vec3d w = xf.indexToWorld(corner);
        box.min = openvdb::math::minComponent(box.min, w);
        box.max = openvdb::math::maxComponent(box.max, w);
    }
    return box;
}

bool VolumeLevel::containsWorld(const Vec3d& p) const {
    const Vec3d i = transform().worldToIndex(p);
    const Vec3d lo = domain.min().asVec3d() - Vec3d(0.5), hi = domain.max().asVec3d() + Vec3d(0.5);
    return i.x() >= lo.x() && i.x() <= hi.x() && i.y() >= lo.y() && i.y() <= hi.y() &&
           i.z() >= lo.z() && i.z() <= hi.z();
}

int finestLevelAt(const LightingVolume& volume, const Vec3d& world) {
    for (int k = int(volume.levels.size()) - 1; k >= 0; --k)
        if (volume.levels[k].containsWorld(world)) return k;
    return -1;
}

LightingVolume LightingVolume::fromLayout(const VolumeLayout& layout) {
    layout.validate();
    LightingVolume volume;
    volume.layout = layout;
    const int r = layout.resolution;
    for (int k = 0; k < layout.levels; ++k) {
        VolumeLevel level;
        level.density = openvdb::FloatGrid::create(0.f);
        level.color = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
        level.density->setTransform(layout.transform(k));
        level.color->setTransform(layout.transform(k));
        level.domain = openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(r - 1));
        level.density->setName(densityGridName(k));
        level.color->setName(colorGridName(k));
        volume.levels.push_back(level);
    }
    volume.normaliseLevels();
    return volume;
}

void LightingVolume::fillLevel(int k, const std::function<MediumSample(const Vec3d&)>& field) {
    if (k < 0 || k >= int(levels.size()))
        throw InputError("fillLevel: no level " + std::to_string(k));
    VolumeLevel& level = levels[k];
    openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> sigma(level.domain, 0.f);
    openvdb::tools::Dense<openvdb::Vec3s, openvdb::tools::LayoutXYZ> color(level.domain,
                                                                           openvdb::Vec3s(0.f));
    const auto& xf = level.transform();
    const openvdb::CoordBBox bbox = level.domain;
    tbb::parallel_for(tbb::blocked_range<int>(bbox.min().x(), bbox.max().x() + 1),
                      [&](const tbb::blocked_range<int>& range) {
                          for (int i = range.begin(); i != range.end(); ++i)
                              for (int j = bbox.min().y(); j <= bbox.max().y(); ++j)
                                  for (int l = bbox.min().z(); l <= bbox.max().z(); ++l) {
                                      const openvdb::Coord ijk(i, j, l);
                                      MediumSample s = field(xf.indexToWorld(ijk));
                                      sigma.setValue(ijk, s.sigma);
                                      color.setValue(ijk,
                                                     s.sigma > 0.f ? s.color : openvdb::Vec3s(0.f));
                                  }
                      });
    level.density->clear();
    level.color->clear();
    // Tolerance 0: only exact zeros (empty space) are left out of the trees.
    openvdb::tools::copyFromDense(sigma, *level.density, 0.f);
    openvdb::tools::copyFromDense(color, *level.color, openvdb::Vec3s(0.f));
}

void LightingVolume::normaliseLevels() {
    std::stable_sort(levels.begin(), levels.end(), [](const VolumeLevel& a, const VolumeLevel& b) {
        return a.voxelVolume() > b.voxelVolume();
    });
    for (std::size_t k = 0; k < levels.size(); ++k) {
        if (k > 0 && std::abs(levels[k].voxelVolume() - levels[k - 1].voxelVolume()) <=
                         1e-9 * levels[k].voxelVolume())
            throw InputError("levels " + std::to_string(k - 1) + " and " + std::to_string(k) +
                             " have the same voxel size: which one is finer is undefined");
        const int level = int(k);
        levels[k].density->setGridClass(openvdb::GRID_FOG_VOLUME);
        levels[k].color->setVectorType(openvdb::VEC_INVARIANT);  // a colour does not transform
        levels[k].density->insertMeta("level", openvdb::Int32Metadata(level));
        levels[k].color->insertMeta("level", openvdb::Int32Metadata(level));
    }
}

void LightingVolume::validate() const {
    if (levels.empty()) throw InputError("lighting volume has no levels");
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const VolumeLevel& l = levels[k];
        const std::string name = "level " + std::to_string(k);
        if (!l.density || !l.color) throw InputError(name + " lacks its density or color grid");
        if (!l.density->transform().isLinear())
            throw InputError(name + ": grid '" + l.density->getName() +
                             "' has a non-affine (frustum) transform, which is not supported");
        if (l.density->transform() != l.color->transform())
            throw InputError(name + ": grids '" + l.density->getName() + "' and '" +
                             l.color->getName() + "' have different transforms");
        if (l.domain.empty()) throw InputError(name + " covers no voxels");
    }
    if (shellCentre && !shellCentre->isFinite())
        throw InputError("the shell's centre is not a finite point");
}

openvdb::Index64 LightingVolume::activeVoxelCount() const {
    openvdb::Index64 n = 0;
    for (const auto& l : levels) n += l.density->activeVoxelCount();
    return n;
}

openvdb::Index64 LightingVolume::memoryBytes() const {
    openvdb::Index64 n = 0;
    for (const auto& l : levels) n += l.density->memUsage() + l.color->memUsage();
    return n;
}

}  // namespace lh
