#include "houdini_export/shells.h"

#include <openvdb/tools/Prune.h>

namespace lh {

namespace {

// True if the voxel centre `ijk` of `level` lies inside any level finer than `k`.
bool coveredByFiner(const LightingVolume& volume, std::size_t k, const openvdb::Coord& ijk) {
    const Vec3d p = volume.levels[k].transform().indexToWorld(ijk);
    for (std::size_t j = k + 1; j < volume.levels.size(); ++j)
        if (volume.levels[j].containsWorld(p)) return true;
    return false;
}

VolumeLevel deepCopy(const VolumeLevel& level) {
    VolumeLevel copy;
    copy.density = level.density->deepCopy();
    copy.color = level.color->deepCopy();
    copy.domain = level.domain;
    // Active tiles become voxels so that single voxels can be switched off.
    copy.density->tree().voxelizeActiveTiles();
    copy.color->tree().voxelizeActiveTiles();
    return copy;
}

}  // namespace

std::vector<VolumeLevel> makeShells(const LightingVolume& volume) {
    std::vector<VolumeLevel> shells;
    for (std::size_t k = 0; k < volume.levels.size(); ++k) {
        VolumeLevel shell = deepCopy(volume.levels[k]);
        if (k + 1 < volume.levels.size()) {
            auto density = shell.density->getAccessor();
            auto color = shell.color->getAccessor();
            std::vector<openvdb::Coord> covered;
            for (auto it = shell.density->cbeginValueOn(); it; ++it)
                if (coveredByFiner(volume, k, it.getCoord())) covered.push_back(it.getCoord());
            for (auto it = shell.color->cbeginValueOn(); it; ++it)
                if (coveredByFiner(volume, k, it.getCoord())) covered.push_back(it.getCoord());
            for (const auto& ijk : covered) {
                density.setValueOff(ijk, 0.f);
                color.setValueOff(ijk, openvdb::Vec3s(0.f));
            }
            openvdb::tools::pruneInactive(shell.density->tree());
            openvdb::tools::pruneInactive(shell.color->tree());
        }
        shells.push_back(shell);
    }
    return shells;
}

void fillCoveredFromFiner(LightingVolume& volume) {
    // Finest first, so a level is complete before its parent averages it.
    for (int k = int(volume.levels.size()) - 2; k >= 0; --k) {
        VolumeLevel& level = volume.levels[k];
        auto density = level.density->getAccessor();
        auto color = level.color->getAccessor();
        const auto& xf = level.transform();
        // Only the part of the domain that finer levels overlap (the domain itself may be huge
        // after an edit grew the coarsest level).
        openvdb::CoordBBox region;
        for (std::size_t f = k + 1; f < volume.levels.size(); ++f) {
            const WorldBox box = volume.levels[f].worldBounds();
            for (int c = 0; c < 8; ++c) {
                const Vec3d corner((c & 1) ? box.max.x() : box.min.x(),
                                   (c & 2) ? box.max.y() : box.min.y(),
                                   (c & 4) ? box.max.z() : box.min.z());
                const Vec3d q = xf.worldToIndex(corner);
                region.expand(openvdb::Coord::floor(q));
                region.expand(openvdb::Coord::ceil(q));
            }
        }
        region.intersect(level.domain);
        if (region.empty()) continue;
        for (auto it = region.begin(); it; ++it) {
            const openvdb::Coord ijk = *it;
            const Vec3d centre = xf.indexToWorld(ijk);
            int j = -1;
            for (int f = int(volume.levels.size()) - 1; f > k && j < 0; --f)
                if (volume.levels[f].containsWorld(centre)) j = f;
            if (j < 0) continue;
            const VolumeLevel& fine = volume.levels[j];
            auto fineDensity = fine.density->getConstAccessor();
            auto fineColor = fine.color->getConstAccessor();
            double sigma = 0;
            openvdb::Vec3d emission(0.0);
            for (int s = 0; s < 8; ++s) {
                // Sub-point at +-1/4 voxel: the centres of the 2x2x2 finer voxels in the layout.
                const Vec3d sub = xf.indexToWorld(Vec3d(ijk.x() + ((s & 1) ? 0.25 : -0.25),
                                                        ijk.y() + ((s & 2) ? 0.25 : -0.25),
                                                        ijk.z() + ((s & 4) ? 0.25 : -0.25)));
                const openvdb::Coord q = openvdb::Coord::round(fine.transform().worldToIndex(sub));
                const float sg = fineDensity.getValue(q);
                sigma += sg;
                emission += openvdb::Vec3d(fineColor.getValue(q)) * double(sg);
            }
            sigma /= 8.0;
            if (sigma > 0) {
                density.setValueOn(ijk, float(sigma));
                color.setValueOn(ijk, openvdb::Vec3s(emission / (8.0 * sigma)));
            } else {
                density.setValueOff(ijk, 0.f);
                color.setValueOff(ijk, openvdb::Vec3s(0.f));
            }
        }
        openvdb::tools::pruneInactive(level.density->tree());
        openvdb::tools::pruneInactive(level.color->tree());
    }
}

}  // namespace lh
