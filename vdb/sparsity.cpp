#include "vdb/sparsity.h"

#include "core/errors.h"

#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/Prune.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lh {

void SparsityOptions::validate() const {
    if (!(std::isfinite(tau) && tau >= 0.0 && tau <= 1.0))
        throw InputError("sparsity bound tau must be in [0, 1] (display radiance units), got " +
                         std::to_string(tau));
    if (maxLevels < 0) throw InputError("maxLevels must be >= 0, got " + std::to_string(maxLevels));
}

int levelsForDepthRange(double near, double far, int maxLevels) {
    if (!(std::isfinite(near) && std::isfinite(far) && near > 0.0 && near <= far))
        throw InputError("depth range needs finite 0 < near <= far, got " + std::to_string(near) +
                         ", " + std::to_string(far));
    if (maxLevels < 1) throw InputError("maxLevels must be >= 1");
    const double s0 = 2.0 * std::min(far, 20.0);
    int levels = 1;
    while (levels < maxLevels && s0 / std::pow(2.0, levels) >= near) ++levels;
    return levels;
}

openvdb::Index64 activeDensityVoxels(const LightingVolume& volume) {
    openvdb::Index64 n = 0;
    for (const auto& level : volume.levels) n += level.density->activeVoxelCount();
    return n;
}

double SparsityBound::thinDensity() const {
    return maxColour > 0 ? fieldBound / maxColour : std::numeric_limits<double>::infinity();
}

SparsityBound sparsityBound(const LightingVolume& volume, double tau) {
    SparsityBound b;
    openvdb::BBoxd box;  // world bounding box of every level's domain (voxel faces)
    for (const auto& level : volume.levels) {
        const openvdb::BBoxd index(level.domain.min().asVec3d() - Vec3d(0.5),
                                   level.domain.max().asVec3d() + Vec3d(0.5));
        box.expand(level.transform().indexToWorld(index));
        auto d = level.density->getConstAccessor();
        for (auto it = level.color->cbeginValueOn(); it; ++it) {
            // Tiles of colour over density tiles: test the tile's first voxel's density.
            if (!(d.getValue(it.getCoord()) > 0.f)) continue;
            b.maxColour =
                std::max({b.maxColour, double(it->x()), double(it->y()), double(it->z())});
        }
    }
    b.rayLength = box.extents().length();
    b.fieldBound = b.rayLength > 0 ? tau / (3.0 * b.rayLength) : 0.0;
    return b;
}

MemoryBreakdown memoryBreakdown(const LightingVolume& volume) {
    MemoryBreakdown m;
    for (const auto& level : volume.levels) {
        const auto& dt = level.density->tree();
        const auto& ct = level.color->tree();
        openvdb::Index64 dl = 0, cl = 0;
        for (auto it = dt.cbeginLeaf(); it; ++it) dl += it->memUsage();
        for (auto it = ct.cbeginLeaf(); it; ++it) cl += it->memUsage();
        m.densityLeaves += dl;
        m.colourLeaves += cl;
        m.densityUpper += level.density->memUsage() - dl;  // root, upper nodes, transform, metadata
        m.colourUpper += level.color->memUsage() - cl;
        m.leafCount += dt.leafCount();
        m.activeVoxels += level.density->activeVoxelCount();
    }
    return m;
}

namespace {

VolumeLevel deepCopy(const VolumeLevel& level) {
    VolumeLevel out;
    out.density = level.density->deepCopy();
    out.color = level.color->deepCopy();
    out.domain = level.domain;
    return out;
}

// Deactivates voxels (and tiles) of density at most `maxSigma` (SparsityBound::thinDensity):
// together they change any ray by at most a third of tau. Returns the voxels dropped.
openvdb::Index64 dropThinVoxels(VolumeLevel& level, double maxSigma) {
    openvdb::Index64 dropped = 0;
    for (auto it = level.density->beginValueOn(); it; ++it) {
        if (*it <= maxSigma) {
            dropped += it.getVoxelCount();
            it.setValue(0.f);
            it.setValueOff();
        }
    }
    return dropped;
}

// Trilinear premultiplied field of one level at world points (what the renderer samples):
// sigma and emission = sigma * colour, inactive voxels empty.
class LevelField {
public:
    explicit LevelField(const VolumeLevel& level) : xf_(level.transform().copy()) {
        emission_ = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
        emission_->setTransform(level.transform().copy());
        sigma_ = openvdb::FloatGrid::create(0.f);
        sigma_->setTransform(level.transform().copy());
        auto e = emission_->getAccessor();
        auto s = sigma_->getAccessor();
        auto c = level.color->getConstAccessor();
        for (auto it = level.density->cbeginValueOn(); it; ++it) {
            openvdb::CoordBBox box;
            it.getBoundingBox(box);
            for (auto ijk = box.begin(); ijk; ++ijk) {
                s.setValue(*ijk, *it);
                e.setValue(*ijk, c.getValue(*ijk) * *it);
            }
        }
        lo_ = level.domain.min().asVec3d() - Vec3d(0.5);
        hi_ = level.domain.max().asVec3d() + Vec3d(0.5);
    }
    // False outside the level's domain.
    bool sample(const Vec3d& world, float& sigma, openvdb::Vec3s& emission) const {
        const Vec3d q = xf_->worldToIndex(world);
        for (int a = 0; a < 3; ++a)
            if (q[a] < lo_[a] || q[a] > hi_[a]) return false;
        auto s = sigma_->getConstAccessor();  // cheap; keeps the object thread-safe
        auto e = emission_->getConstAccessor();
        sigma = openvdb::tools::BoxSampler::sample(s, q);
        emission = openvdb::tools::BoxSampler::sample(e, q);
        return true;
    }

private:
    openvdb::math::Transform::Ptr xf_;
    openvdb::FloatGrid::Ptr sigma_;
    openvdb::Vec3SGrid::Ptr emission_;
    Vec3d lo_, hi_;
};

// Bounding box of the voxels of `fine` that the coarser fields do not reproduce within tau
// (empty if they reproduce all of it).
// `eps` is SparsityBound::fieldBound, `colour` its brightest colour C.
openvdb::CoordBBox unreproducedBox(const VolumeLevel& fine, const std::vector<LevelField>& coarser,
                                   double eps, double colour) {
    const openvdb::CoordBBox domain = fine.domain;
    using Range = tbb::blocked_range<int>;
    return tbb::parallel_reduce(
        Range(domain.min().z(), domain.max().z() + 1), openvdb::CoordBBox(),
        [&](const Range& zs, openvdb::CoordBBox box) {
            auto d = fine.density->getConstAccessor();
            auto c = fine.color->getConstAccessor();
            for (int z = zs.begin(); z != zs.end(); ++z)
                for (int y = domain.min().y(); y <= domain.max().y(); ++y)
                    for (int x = domain.min().x(); x <= domain.max().x(); ++x) {
                        const openvdb::Coord ijk(x, y, z);
                        float sigma = 0.f;
                        if (!d.probeValue(ijk, sigma)) sigma = 0.f;
                        const openvdb::Vec3s emission =
                            sigma > 0.f ? c.getValue(ijk) * sigma : openvdb::Vec3s(0.f);
                        const Vec3d world = fine.transform().indexToWorld(ijk);
                        float sc = 0.f;
                        openvdb::Vec3s ec(0.f);
                        bool inside = false;
                        for (auto it = coarser.rbegin(); it != coarser.rend() && !inside; ++it)
                            inside = it->sample(world, sc, ec);
                        double de = 0;
                        for (int i = 0; i < 3; ++i)
                            de = std::max(de, double(std::abs(emission[i] - ec[i])));
                        const bool same =
                            inside && de + colour * std::abs(double(sigma) - sc) <= eps;
                        if (!same) box.expand(ijk);
                    }
            return box;
        },
        [](openvdb::CoordBBox a, const openvdb::CoordBBox& b) {
            a.expand(b);
            return a;
        });
}

// Tile tolerances from the field bound: prune moves a value by at most twice its tolerance;
// a density change d moves emission by up to C d as well, a colour change c by sigma_max c.
// With tolS = eps / (6 C) and tolC = eps / (6 sigma_max):
//   |d_e| + C |d_sigma| <= (2 C tolS + 2 sigma_max tolC) + 2 C tolS = eps.
void pruneLevel(VolumeLevel& level, double eps, double colour, bool tiles) {
    // Colour matters only where there is density.
    level.color->tree().topologyIntersection(level.density->tree());
    if (tiles && eps > 0) {
        float sigmaMax = 0.f;
        for (auto it = level.density->cbeginValueOn(); it; ++it) sigmaMax = std::max(sigmaMax, *it);
        const double big = std::numeric_limits<float>::max();
        const float tolS = float(colour > 0 ? std::min(big, eps / (6 * colour)) : big);
        const float tolC = float(sigmaMax > 0 ? std::min(big, eps / (6 * double(sigmaMax))) : big);
        openvdb::tools::prune(level.density->tree(), tolS);
        openvdb::tools::prune(level.color->tree(), openvdb::Vec3s(tolC));
    }
    openvdb::tools::pruneInactive(level.density->tree());
    openvdb::tools::pruneInactive(level.color->tree());
}

}  // namespace

LightingVolume sparsify(const LightingVolume& volume, const SparsityOptions& options,
                        SparsityStats* stats) {
    options.validate();
    volume.validate();
    SparsityStats s;
    s.activeBefore = activeDensityVoxels(volume);
    s.memoryBefore = volume.memoryBytes();

    LightingVolume out;
    out.layout = volume.layout;
    out.refCamera = volume.refCamera;
    out.shellCentre = volume.shellCentre;
    std::size_t keep = volume.levels.size();
    if (options.maxLevels > 0 && std::size_t(options.maxLevels) < keep) keep = options.maxLevels;
    s.levelsDropped += int(volume.levels.size() - keep);
    for (std::size_t k = 0; k < keep; ++k) out.levels.push_back(deepCopy(volume.levels[k]));

    // The bound is derived from the input (all its levels): dropping levels never lengthens a
    // ray or brightens a colour.
    const SparsityBound bound = sparsityBound(volume, options.tau);
    s.rayLength = bound.rayLength;
    s.maxColour = bound.maxColour;
    s.fieldBound = bound.fieldBound;
    if (options.dropThinVoxels)
        for (auto& level : out.levels)
            s.thinVoxelsDropped += dropThinVoxels(level, bound.thinDensity());

    if (options.dropReproducedFine && out.levels.size() > 1) {
        std::vector<VolumeLevel> kept{out.levels[0]};
        std::vector<LevelField> fields;
        fields.emplace_back(kept[0]);
        for (std::size_t k = 1; k < out.levels.size(); ++k) {
            VolumeLevel& level = out.levels[k];
            openvdb::CoordBBox box =
                unreproducedBox(level, fields, bound.fieldBound, bound.maxColour);
            const openvdb::Index64 before = level.density->activeVoxelCount();
            if (box.empty()) {
                s.reproducedVoxelsDropped += before;
                ++s.levelsDropped;
                continue;
            }
            // One voxel of margin: lookups just inside the new edge still read this level.
            box.expand(1);
            box.intersect(level.domain);
            if (box != level.domain) {
                level.density->clip(box);
                level.color->clip(box);
                level.domain = box;
                s.reproducedVoxelsDropped += before - level.density->activeVoxelCount();
            }
            kept.push_back(level);
            fields.emplace_back(level);
        }
        out.levels = std::move(kept);
    }
    // A dropped middle level breaks the layout's level numbering; dropping only the finest
    // levels keeps it with a smaller count.
    if (out.layout && out.levels.size() != volume.levels.size()) {
        bool prefix = true;
        for (std::size_t k = 0; k < out.levels.size() && prefix; ++k)
            prefix = out.levels[k].transform() == volume.levels[k].transform();
        if (prefix)
            out.layout->levels = int(out.levels.size());
        else
            out.layout.reset();
    }
    for (auto& level : out.levels)
        pruneLevel(level, bound.fieldBound, bound.maxColour, options.pruneTiles);
    out.normaliseLevels();
    s.activeAfter = activeDensityVoxels(out);
    s.memoryAfter = out.memoryBytes();
    if (stats) *stats = s;
    return out;
}

VolumeSaveReport saveSparseVolume(const std::string& path, const LightingVolume& volume,
                                  bool halfPrecision, int mantissaBits) {
    return saveVolume(path, volume, VolumeSaveOptions{halfPrecision, mantissaBits});
}

}  // namespace lh
