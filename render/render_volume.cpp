#include "render/render_volume.h"

#include "render/medium_boxes.h"

#include "core/cpu_dispatch.h"
#include "core/errors.h"

#include <openvdb/tools/FindActiveValues.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace lh {

namespace {

constexpr int kLatticeValues =
    RenderLevel::kLattice * RenderLevel::kLattice * RenderLevel::kLattice;

// Defensive clamps: the loader already sanitises files; volumes built in memory may not be.
float cleanSigma(float s) {
    return std::isfinite(s) && s > 0.f ? std::min(s, 1e15f) : (s > 0.f ? 1e15f : 0.f);
}
float cleanRadiance(float c) {
    return std::isfinite(c) && c > 0.f ? std::min(c, 1e15f) : (c > 0.f ? 1e15f : 0.f);
}

// The part t >= 0 of a level ray inside [lo, hi]; false when it misses.
inline bool intersectBox(const LevelRay& ray, const Vec3d& lo, const Vec3d& hi, double& tNear,
                         double& tFar) {
    tNear = 0.0;
    tFar = std::numeric_limits<double>::infinity();
    return clipToBox(lo.asPointer(), hi.asPointer(), ray.q0, ray.qd, ray.inv, tNear, tFar);
}

// Appends the occupancy words of one brick's lattice (RenderLevel::cellMask) and the box
// around its occupied cells (RenderLevel::cellBox).
void appendCellOccupancy(const std::vector<float>& lattice, std::vector<uint64_t>& masks,
                         std::vector<RenderLevel::CellBox>& boxes) {
    constexpr int n = RenderLevel::kLattice, cells = RenderLevel::kBrick;
    const auto dense = [&](int x, int y, int z) {
        return lattice[std::size_t((z * n + y) * n + x) * 4] > 0.f;
    };
    RenderLevel::CellBox box{{cells, cells, cells}, {0, 0, 0}};
    for (int z = 0; z < cells; ++z) {
        uint64_t word = 0;
        for (int y = 0; y < cells; ++y)
            for (int x = 0; x < cells; ++x) {
                bool any = false;
                for (int c = 0; c < 8 && !any; ++c)
                    any = dense(x + (c & 1), y + ((c >> 1) & 1), z + (c >> 2));
                if (!any) continue;
                word |= uint64_t(1) << (x + cells * y);
                const int at[3] = {x, y, z};
                for (int a = 0; a < 3; ++a) {
                    box.lo[a] = uint8_t(std::min<int>(box.lo[a], at[a]));
                    box.hi[a] = uint8_t(std::max<int>(box.hi[a], at[a] + 1));
                }
            }
        masks.push_back(word);
    }
    boxes.push_back(box);
}

// True if the box of `inner` lies inside the box of `outer` (both in world space), up to
// 1e-6 voxels of `outer` for the rounding of the two transforms.
bool boxInside(const RenderLevel& inner, const RenderLevel& outer) {
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3d q(corner & 1 ? inner.domainHi.x() : inner.domainLo.x(),
                      corner & 2 ? inner.domainHi.y() : inner.domainLo.y(),
                      corner & 4 ? inner.domainHi.z() : inner.domainLo.z());
        const Vec3d p = outer.toIndex(inner.indexToWorld * (q - inner.indexOffset));
        for (int a = 0; a < 3; ++a)
            if (p[a] < outer.domainLo[a] - 1e-6 || p[a] > outer.domainHi[a] + 1e-6) return false;
    }
    return true;
}

RenderLevel prepareLevel(const VolumeLevel& level, const std::vector<RenderLevel>& coarser) {
    RenderLevel out;
    const auto& xf = level.transform();
    const Vec3d origin = xf.indexToWorld(Vec3d(0.0));
    Mat3d toWorld;
    toWorld.setColumns(xf.indexToWorld(Vec3d(1, 0, 0)) - origin,
                       xf.indexToWorld(Vec3d(0, 1, 0)) - origin,
                       xf.indexToWorld(Vec3d(0, 0, 1)) - origin);
    out.indexToWorld = toWorld;
    out.worldToIndex = toWorld.inverse();
    const Mat3d& m = out.worldToIndex;
    out.axisAligned = m(0, 1) == 0 && m(0, 2) == 0 && m(1, 0) == 0 && m(1, 2) == 0 &&
                      m(2, 0) == 0 && m(2, 1) == 0;
    out.indexOffset = -(out.worldToIndex * origin);
    out.voxelVolume = std::abs(toWorld.det());

    const openvdb::CoordBBox domain = level.domain;
    out.domainLo = domain.min().asVec3d() - Vec3d(0.5);
    out.domainHi = domain.max().asVec3d() + Vec3d(0.5);
    out.latticeOrigin = domain.min() - openvdb::Coord(1);
    std::size_t cells = 1;
    for (int a = 0; a < 3; ++a) {
        // Trilinear lookups inside the domain use lattice points min-1 .. max+1.
        const int64_t points = int64_t(domain.max()[a]) - domain.min()[a] + 2;
        out.brickCount[a] = int((points + RenderLevel::kBrick - 1) / RenderLevel::kBrick);
        cells *= std::size_t(out.brickCount[a]);
        if (cells > kMaxBrickCells)
            throw ResourceError("a volume level spans " + std::to_string(domain.dim().x()) + " x " +
                                std::to_string(domain.dim().y()) + " x " +
                                std::to_string(domain.dim().z()) +
                                " voxels, more than the renderer's bound; crop or resample it");
    }

    // Halo value at an index point outside the domain: the next coarser level containing it,
    // else the nearest edge voxel of this level.
    auto haloValue = [&](const openvdb::Coord& c, auto& densityAcc, auto& colorAcc, float* v) {
        const Vec3d world = toWorld * c.asVec3d() + origin;
        for (int k = int(coarser.size()) - 1; k >= 0; --k) {
            const RenderLevel& parent = coarser[k];
            const Vec3d q = parent.toIndex(world);
            if (parent.containsIndex(q)) {
                RenderSample s = parent.sample(q);
                v[0] = s.sigma;
                std::copy(s.emission, s.emission + 3, v + 1);
                return;
            }
        }
        const openvdb::Coord clamped = openvdb::Coord::maxComponent(
            domain.min(), openvdb::Coord::minComponent(domain.max(), c));
        float sigma = 0.f;
        if (!densityAcc.probeValue(clamped, sigma)) sigma = 0.f;
        sigma = cleanSigma(sigma);
        const openvdb::Vec3s color = colorAcc.getValue(clamped);
        v[0] = sigma;
        for (int i = 0; i < 3; ++i) v[1 + i] = sigma * cleanRadiance(color[i]);
    };

    const int bricks = int(cells);
    // Brick cell (x, y, z) of table index b (x fastest, as in brickIndex).
    const auto brickCoordinates = [&](int b) {
        return std::array<int, 3>{b % out.brickCount[0],
                                  (b / out.brickCount[0]) % out.brickCount[1],
                                  b / (out.brickCount[0] * out.brickCount[1])};
    };
    std::vector<std::vector<float>> lattice(bricks);
    tbb::parallel_for(
        tbb::blocked_range<int>(0, bricks), [&](const tbb::blocked_range<int>& range) {
            auto densityAcc = level.density->getConstAccessor();  // accessors are per task
            auto colorAcc = level.color->getConstAccessor();
            for (int b = range.begin(); b != range.end(); ++b) {
                const auto [bx, by, bz] = brickCoordinates(b);
                const openvdb::Coord lo =
                    out.latticeOrigin + openvdb::Coord(bx * RenderLevel::kBrick,
                                                       by * RenderLevel::kBrick,
                                                       bz * RenderLevel::kBrick);
                const openvdb::CoordBBox points(lo, lo + openvdb::Coord(RenderLevel::kBrick));
                openvdb::CoordBBox inside = points;
                inside.intersect(domain);
                const bool touchesHalo = !domain.isInside(points);
                if (!touchesHalo && !openvdb::tools::anyActiveValues(level.density->tree(), inside))
                    continue;  // empty interior brick: nothing to store
                std::vector<float> values(std::size_t(kLatticeValues) * 4, 0.f);
                bool anyDensity = false;
                for (int z = 0; z < RenderLevel::kLattice; ++z)
                    for (int y = 0; y < RenderLevel::kLattice; ++y)
                        for (int x = 0; x < RenderLevel::kLattice; ++x) {
                            const openvdb::Coord c = lo + openvdb::Coord(x, y, z);
                            float* v = &values[std::size_t((z * RenderLevel::kLattice + y) *
                                                               RenderLevel::kLattice +
                                                           x) *
                                               4];
                            // Lattice points beyond max+1 are never read by lookups in the domain.
                            if (c.x() > domain.max().x() + 1 || c.y() > domain.max().y() + 1 ||
                                c.z() > domain.max().z() + 1)
                                continue;
                            if (domain.isInside(c)) {
                                float sigma = 0.f;
                                if (!densityAcc.probeValue(c, sigma))
                                    sigma = 0.f;  // inactive = empty
                                sigma = cleanSigma(sigma);
                                const openvdb::Vec3s color = colorAcc.getValue(c);
                                v[0] = sigma;
                                for (int i = 0; i < 3; ++i)
                                    v[1 + i] = sigma * cleanRadiance(color[i]);
                            } else {
                                haloValue(c, densityAcc, colorAcc, v);
                            }
                            anyDensity |= v[0] > 0.f;
                        }
                if (anyDensity) lattice[b] = std::move(values);
            }
        });

    out.brickTable.assign(cells, -1);
    std::size_t stored = 0;
    for (int b = 0; b < bricks; ++b) stored += !lattice[b].empty();
    if (stored > kMaxStoredBricks)
        throw ResourceError("a volume level holds " + std::to_string(stored) +
                            " non-empty bricks, more than the renderer's memory bound");
    out.brickData.reserve(stored * kLatticeValues * 4);
    int32_t next = 0;
    for (int b = 0; b < bricks; ++b) {
        if (lattice[b].empty()) continue;
        out.brickTable[b] = next++;
        out.brickData.insert(out.brickData.end(), lattice[b].begin(), lattice[b].end());
        appendCellOccupancy(lattice[b], out.cellMasks, out.cellBoxes);
        const RenderLevel::CellBox& box = out.cellBoxes.back();
        const std::array<int, 3> brick = brickCoordinates(b);
        for (int a = 0; a < 3; ++a) {
            out.occupiedLo[a] =
                std::min(out.occupiedLo[a], double(brick[a] * RenderLevel::kBrick + box.lo[a]));
            out.occupiedHi[a] =
                std::max(out.occupiedHi[a], double(brick[a] * RenderLevel::kBrick + box.hi[a]));
        }
    }
    return out;
}

}  // namespace

RenderSample RenderLevel::sample(const Vec3d& index) const {
    // Continuous lattice coordinates relative to the lattice origin.
    const double u[3] = {index.x() - latticeOrigin.x(), index.y() - latticeOrigin.y(),
                         index.z() - latticeOrigin.z()};
    int brick[3];
    float local[3];
    for (int a = 0; a < 3; ++a) {
        const int maxCell = brickCount[a] * kBrick - 1;
        const int i = std::clamp(int(std::floor(u[a])), 0, maxCell);
        brick[a] = i >> kBrickLog2;
        local[a] = float(std::clamp(u[a] - (brick[a] << kBrickLog2), 0.0, double(kBrick)));
    }
    const int b = brickIndex(brick[0], brick[1], brick[2]);
    if (b < 0) return {0.f, {0.f, 0.f, 0.f}};
    return sampleLattice(brickPointer(b), local[0], local[1], local[2]);
}

bool RenderLevel::brickOccupied(int bx, int by, int bz) const {
    if (bx < 0 || by < 0 || bz < 0 || bx >= brickCount[0] || by >= brickCount[1] ||
        bz >= brickCount[2])
        return false;
    return brickIndex(bx, by, bz) >= 0;
}

namespace {

// RenderVolume::typicalRadiance over the prepared lattices, from at most ~1M points (strided).
double typicalSurfaceRadiance(const std::vector<RenderLevel>& levels) {
    std::size_t points = 0;
    for (const RenderLevel& level : levels) points += level.brickData.size() / 4;
    const std::size_t stride = std::max<std::size_t>(1, points >> 20);
    std::vector<float> brightness;
    std::size_t index = 0;
    for (const RenderLevel& level : levels)
        for (std::size_t p = 0; p < level.brickData.size(); p += 4, ++index) {
            const float* v = &level.brickData[p];  // sigma, emission rgb
            if (index % stride != 0 || !(v[0] > 0.f)) continue;
            const float b = std::max({v[1], v[2], v[3]}) / v[0];
            if (std::isfinite(b)) brightness.push_back(b);
        }
    if (brightness.empty()) return 0.0;
    const auto middle = brightness.begin() + std::ptrdiff_t(brightness.size() / 2);
    std::nth_element(brightness.begin(), middle, brightness.end());
    if (*middle > 0.f) return *middle;
    double sum = 0.0;
    for (float b : brightness) sum += b;
    return sum / double(brightness.size());
}

}  // namespace

RenderVolume::RenderVolume(const LightingVolume& volume) {
    volume.validate();
    if (volume.levels.size() > std::size_t(kMaxLevels))
        throw InputError("the volume has " + std::to_string(volume.levels.size()) +
                         " levels; the renderer supports at most " + std::to_string(kMaxLevels));
    std::size_t stored = 0;
    for (const VolumeLevel& level : volume.levels) {
        levels.push_back(prepareLevel(level, levels));
        stored += levels.back().brickData.size() / (kLatticeValues * 4);
        if (stored > kMaxStoredBricks)
            throw ResourceError(
                "the volume holds more non-empty bricks than the renderer's "
                "memory bound (" +
                std::to_string(kMaxStoredBricks) + ")");
    }
    nested_ = true;
    for (std::size_t k = 1; k < levels.size(); ++k)
        nested_ = nested_ && boxInside(levels[k], levels[k - 1]);
    axisAligned_ = std::all_of(levels.begin(), levels.end(),
                               [](const RenderLevel& l) { return l.axisAligned; });
    typicalRadiance_ = typicalSurfaceRadiance(levels);
    mediumBoxesValid_ = boundMedium(levels, mediumBoxes_);
}

RenderVolume::RayOrigin RenderVolume::rayOrigin(const Vec3d& world) const {
    RayOrigin origin;
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const RenderLevel& level = levels[k];
        const Vec3d q = level.toIndex(world);
        origin.index[k] = q;
        if (!level.axisAligned) continue;
        for (int a = 0; a < 3; ++a) {  // index offsets times the voxel size (signed)
            origin.toLowFace[k][a] = (level.domainLo[a] - q[a]) * level.indexToWorld(a, a);
            origin.toHighFace[k][a] = (level.domainHi[a] - q[a]) * level.indexToWorld(a, a);
        }
    }
    return origin;
}

LH_PER_CPU  // core/cpu_dispatch.h: 2.8% fewer instructions per envmap on x86-64-v3
    int
    RenderVolume::partitionRay(const RayOrigin& origin, const Vec3d& dir, Piece* pieces) const {
    if (!nested_) return partitionRayGeneral(origin, dir, pieces);
    // Nested boxes: the ray's interval in a finer level lies inside its interval in every
    // coarser level, so the pieces, in ray order, are the coarser levels' entry parts
    // (coarsest first), the finest level hit, then their exit parts (finest first).
    const int n = int(levels.size());
    double lo[kMaxPieces], hi[kMaxPieces];
    int hit = 0;  // levels 0 .. hit-1 are hit (a level missed means every finer one is too)
    const Vec3d invDir(1.0 / dir.x(), 1.0 / dir.y(), 1.0 / dir.z());
    if (axisAligned_ && std::isfinite(invDir.x()) && std::isfinite(invDir.y()) &&
        std::isfinite(invDir.z())) {
        // Slab tests in scene units, three products per level and no division. (A zero
        // component would make 0 x inf; those rays take the index-space test below.)
        for (; hit < n; ++hit) {
            double tNear = 0.0, tFar = std::numeric_limits<double>::infinity();
            for (int a = 0; a < 3; ++a) {
                const double t0 = origin.toLowFace[hit][a] * invDir[a],
                             t1 = origin.toHighFace[hit][a] * invDir[a];
                tNear = std::max(tNear, std::min(t0, t1));
                tFar = std::min(tFar, std::max(t0, t1));
            }
            if (!(tNear < tFar)) break;
            lo[hit] = tNear, hi[hit] = tFar;
        }
    } else {
        for (; hit < n; ++hit) {
            const RenderLevel& level = levels[hit];
            const LevelRay ray = level.rayFromIndexOrigin(origin.index[hit], dir);
            if (!intersectBox(ray, level.domainLo, level.domainHi, lo[hit], hi[hit])) break;
        }
    }
    int count = 0;
    for (int k = 0; k + 1 < hit; ++k)
        if (lo[k + 1] > lo[k]) pieces[count++] = {lo[k], lo[k + 1], k};
    if (hit > 0) pieces[count++] = {lo[hit - 1], hi[hit - 1], hit - 1};
    for (int k = hit - 2; k >= 0; --k)
        if (hi[k] > hi[k + 1]) pieces[count++] = {hi[k + 1], hi[k], k};
    // At most two pieces per coarser level and one for the finest, in ray order.
    LH_DCHECK(count <= 2 * n - 1 && count <= kMaxPieces);
    for (int p = 1; p < count; ++p)
        LH_DCHECK(pieces[p].t0 >= pieces[p - 1].t1 - 1e-9 * (1 + std::abs(pieces[p].t0)));
    return count;
}

int RenderVolume::partitionRayGeneral(const RayOrigin& origin, const Vec3d& dir,
                                      Piece* pieces) const {
    int count = 0;
    // Finest first: each level claims the parts of its interval no finer level has claimed.
    for (int k = int(levels.size()) - 1; k >= 0; --k) {
        const RenderLevel& level = levels[k];
        double a, b;
        const LevelRay ray = level.rayFromIndexOrigin(origin.index[k], dir);
        if (!intersectBox(ray, level.domainLo, level.domainHi, a, b)) continue;
        // Subtract claimed intervals from [a, b]; claimed pieces are disjoint.
        double free0[kMaxPieces + 1], free1[kMaxPieces + 1];
        int nFree = 1;
        free0[0] = a;
        free1[0] = b;
        for (int p = 0; p < count; ++p) {
            int nNext = 0;
            double next0[kMaxPieces + 1], next1[kMaxPieces + 1];
            for (int f = 0; f < nFree; ++f) {
                if (pieces[p].t1 <= free0[f] || pieces[p].t0 >= free1[f]) {
                    next0[nNext] = free0[f], next1[nNext++] = free1[f];
                    continue;
                }
                if (free0[f] < pieces[p].t0 && nNext < kMaxPieces)
                    next0[nNext] = free0[f], next1[nNext++] = pieces[p].t0;
                if (pieces[p].t1 < free1[f] && nNext < kMaxPieces)
                    next0[nNext] = pieces[p].t1, next1[nNext++] = free1[f];
            }
            std::copy(next0, next0 + nNext, free0);
            std::copy(next1, next1 + nNext, free1);
            nFree = nNext;
        }
        for (int f = 0; f < nFree && count < kMaxPieces; ++f)
            if (free1[f] > free0[f]) pieces[count++] = {free0[f], free1[f], k};
    }
    std::sort(pieces, pieces + count, [](const Piece& x, const Piece& y) { return x.t0 < y.t0; });
    return count;
}

RenderSample RenderVolume::sampleWorld(const Vec3d& world) const {
    for (int k = int(levels.size()) - 1; k >= 0; --k) {
        const RenderLevel& level = levels[k];
        const Vec3d q = level.toIndex(world);
        if (level.containsIndex(q)) return level.sample(q);
    }
    return {0.f, {0.f, 0.f, 0.f}};
}

double RenderVolume::voxelSizeAt(const Vec3d& world) const {
    for (int k = int(levels.size()) - 1; k >= 0; --k) {
        if (levels[k].containsIndex(levels[k].toIndex(world)))
            return std::cbrt(levels[k].voxelVolume);
    }
    return 0.0;
}

std::size_t RenderVolume::storedBricks() const {
    std::size_t n = 0;
    for (const auto& l : levels) n += l.brickData.size() / (kLatticeValues * 4);
    return n;
}

std::size_t RenderVolume::memoryBytes() const {
    std::size_t n = 0;
    for (const auto& l : levels)
        n += l.brickData.size() * sizeof(float) + l.brickTable.size() * sizeof(int32_t) +
             l.cellMasks.size() * sizeof(uint64_t) +
             l.cellBoxes.size() * sizeof(RenderLevel::CellBox);
    return n;
}

}  // namespace lh
