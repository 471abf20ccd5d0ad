// A lighting volume prepared for fast rendering.
//
// Each level becomes a sparse set of 8^3-voxel bricks in its own index space. A brick stores a
// 9^3 lattice of (sigma, sigma*r, sigma*g, sigma*b) so that a trilinear lookup reads one
// contiguous block: sigma and the premultiplied emission are interpolated
// (docs/conventions.md#interpolation), colour = emission / sigma. Bricks whose lattice has no
// density are not stored; the marcher skips them without sampling.
//
// No seams: a level's lattice includes a one-voxel halo outside its domain, filled from the
// next coarser level that contains the halo point (or, with none, by repeating the edge voxel).
// Trilinear lookups just inside a finer level therefore blend towards the coarser level's field
// instead of towards empty space, and the coarser level is never zeroed where finer levels are.
// Inactive voxels count as empty space.
#pragma once

#include "core/check.h"

#include "vdb/lighting_volume.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace lh {

struct Piece;

// A ray in one level's continuous index coordinates: q(t) = q0 + t qd, t in scene units along
// the world ray, with the reciprocals of qd's components (infinite where a component is 0)
// so that the DDAs multiply instead of divide.
struct LevelRay {
    Vec3d q0, qd, inv;
};

// Slab test: narrows [ta, tb] to the part of u(t) = u0 + t qd inside the box [lo, hi], with
// inv = 1 / qd (infinite where a component is 0); false if nothing is left.
inline bool clipToBox(const double lo[3], const double hi[3], const Vec3d& u0, const Vec3d& qd,
                      const Vec3d& inv, double& ta, double& tb) {
    for (int a = 0; a < 3; ++a) {
        if (qd[a] == 0.0) {  // parallel to the box's faces on this axis (0 x inf is NaN)
            if (u0[a] < lo[a] || u0[a] > hi[a]) return false;
            continue;
        }
        const double tLo = (lo[a] - u0[a]) * inv[a], tHi = (hi[a] - u0[a]) * inv[a];
        ta = std::max(ta, std::min(tLo, tHi));
        tb = std::min(tb, std::max(tLo, tHi));
    }
    return ta < tb;
}

// Medium sample in the render representation.
struct RenderSample {
    float sigma;        // extinction, per scene unit
    float emission[3];  // sigma * colour
};

// Four floats as one SIMD register (the channels of a lattice point), and what sampling does
// with them.
using Float4 = float __attribute__((vector_size(16)));
inline Float4 load4(const float* p) {
    Float4 v;
    std::memcpy(&v, p, sizeof v);  // unaligned load
    return v;
}
inline Float4 lerp(Float4 a, Float4 b, float f) { return a + f * (b - a); }

class RenderLevel {
public:
    static constexpr int kBrickLog2 = 3;
    static constexpr int kBrick = 1 << kBrickLog2;  // voxels per brick side
    static constexpr int kLattice = kBrick + 1;     // lattice points per brick side (apron)

    // World -> continuous index coordinates (voxel centres at integers).
    Vec3d toIndex(const Vec3d& world) const { return worldToIndex * world + indexOffset; }
    Vec3d directionToIndex(const Vec3d& dir) const { return worldToIndex * dir; }
    LevelRay ray(const Vec3d& origin, const Vec3d& dir) const {
        return rayFromIndexOrigin(toIndex(origin), dir);
    }
    // The same with the origin already in index coordinates (RenderVolume::RayOrigin): only the
    // direction is mapped, with three products when the level's axes are the world's.
    LevelRay rayFromIndexOrigin(const Vec3d& q0, const Vec3d& dir) const {
        const Vec3d qd = axisAligned
                             ? Vec3d(worldToIndex(0, 0) * dir.x(), worldToIndex(1, 1) * dir.y(),
                                     worldToIndex(2, 2) * dir.z())
                             : directionToIndex(dir);
        return {q0, qd, Vec3d(1.0 / qd.x(), 1.0 / qd.y(), 1.0 / qd.z())};
    }

    // True if continuous index coordinates lie inside the domain's outer voxel faces.
    bool containsIndex(const Vec3d& q) const {
        return q.x() >= domainLo.x() && q.x() <= domainHi.x() && q.y() >= domainLo.y() &&
               q.y() <= domainHi.y() && q.z() >= domainLo.z() && q.z() <= domainHi.z();
    }
    // Trilinear sample at continuous index coordinates. Valid inside [domainLo, domainHi].
    RenderSample sample(const Vec3d& index) const;
    // Trilinear sample inside one stored brick: `brick` points at its kLattice^3 x 4 floats,
    // (u, v, w) are lattice coordinates relative to its first lattice point, in [0, kBrick]
    // (clamped). The marcher's inner loop: no table lookup, no bounds logic beyond the clamp.
    static RenderSample sampleLattice(const float* brick, float u, float v, float w) {
        const int i = std::clamp(int(u), 0, kBrick - 1), j = std::clamp(int(v), 0, kBrick - 1),
                  k = std::clamp(int(w), 0, kBrick - 1);
        return sampleCell(brick + (k * kLatticeZ + j * kLatticeY + i * 4), u - float(i),
                          v - float(j), w - float(k));
    }
    // Trilinear sample inside one lattice cell: `corner` points at its (0, 0, 0) lattice point
    // (+4 floats is +x, +kLatticeY is +y, +kLatticeZ is +z), (fx, fy, fz) in [0, 1] (clamped).
    static constexpr int kLatticeY = kLattice * 4, kLatticeZ = kLattice * kLattice * 4;
    //
    // The four channels of a lattice point are one 16-byte vector (GCC's and Clang's vector
    // extension): the seven lerps run on all four at once. Written as a loop over channels,
    // the compiler vectorised it in some inlined copies of the marcher and not in others
    // (3.7x the instructions of the sample there).
    static RenderSample sampleCell(const float* p, float fx, float fy, float fz) {
        fx = std::clamp(fx, 0.f, 1.f), fy = std::clamp(fy, 0.f, 1.f), fz = std::clamp(fz, 0.f, 1.f);
        constexpr int sy = kLatticeY, sz = kLatticeZ;
        // Lerps: exact for equal corners (constant media).
        const Float4 c00 = lerp(load4(p), load4(p + 4), fx),
                     c10 = lerp(load4(p + sy), load4(p + sy + 4), fx),
                     c01 = lerp(load4(p + sz), load4(p + sz + 4), fx),
                     c11 = lerp(load4(p + sz + sy), load4(p + sz + sy + 4), fx);
        const Float4 out = lerp(lerp(c00, c10, fy), lerp(c01, c11, fy), fz);
        return {out[0], {out[1], out[2], out[3]}};
    }
    // Occupancy of a stored brick's 8^3 lattice cells: bit (x + 8 y) of word z is set if any of
    // the cell's eight corners (x..x+1, y..y+1, z..z+1) has density.
    const uint64_t* cellMask(int stored) const {
        return cellMasks.data() + std::size_t(stored) * kBrick;
    }
    // The box around a stored brick's occupied cells, in cells [lo, hi) per axis. Every cell
    // outside it is empty, so a ray walks only the part of the brick inside it (and skips a
    // brick whose box it misses): a wall two voxels thick fills a box two cells thick.
    struct CellBox {
        uint8_t lo[3], hi[3];
    };
    const CellBox& cellBox(int stored) const { return cellBoxes[std::size_t(stored)]; }
    const float* brickPointer(int stored) const {
        return brickData.data() + std::size_t(stored) * kLattice * kLattice * kLattice * 4;
    }
    // True if the brick cell at brick coordinates (bx, by, bz) holds density.
    bool brickOccupied(int bx, int by, int bz) const;
    int brickIndex(int bx, int by, int bz) const {
        LH_DCHECK(bx >= 0 && bx < brickCount[0] && by >= 0 && by < brickCount[1] && bz >= 0 &&
                  bz < brickCount[2]);
        return brickTable[(std::size_t(bz) * brickCount[1] + by) * brickCount[0] + bx];
    }

    Mat3d worldToIndex;            // linear part of the world -> index map
    bool axisAligned = false;      // worldToIndex is diagonal (the usual layout)
    Vec3d indexOffset;             // translation of the world -> index map
    Mat3d indexToWorld;            // inverse linear part (for halo positions)
    Vec3d domainLo, domainHi;      // continuous index bounds: outer faces of the domain's voxels
    openvdb::Coord latticeOrigin;  // index coordinate of lattice point (0,0,0) of brick (0,0,0)
    std::array<int, 3> brickCount{0, 0, 0};
    std::vector<int32_t> brickTable;  // -1 = empty brick
    std::vector<float> brickData;     // kLattice^3 x 4 floats per stored brick
    std::vector<uint64_t> cellMasks;  // kBrick words per stored brick (cellMask)
    std::vector<CellBox> cellBoxes;   // one per stored brick (cellBox)
    // The box around every occupied cell of the level, in lattice coordinates (relative to
    // latticeOrigin): the field is zero outside it, so a ray walks only its part inside.
    // Empty (lo > hi) when the level stores no brick.
    Vec3d occupiedLo{std::numeric_limits<double>::max()},
        occupiedHi{std::numeric_limits<double>::lowest()};
    double voxelVolume = 0;  // scene units^3
};

// A box in scene units (world frame) outside which a volume's field is zero: see
// RenderVolume::mediumBoxes.
struct MediumBox {
    double lo[3], hi[3];
};

class RenderVolume {
public:
    // Prepares every level (coarsest first, as in the volume). Throws ResourceError if a level
    // would need more than the documented memory bound.
    explicit RenderVolume(const LightingVolume& volume);

    std::vector<RenderLevel> levels;  // coarsest first

    // Ray partition by the finest-wins rule: the ordered t-intervals of a ray (origin, unit
    // direction) and the level that defines the medium on each. Returns the piece count.
    static constexpr int kMaxPieces = 64;
    static constexpr int kMaxLevels = 32;  // the constructor refuses more (InputError)
    // What every ray from one origin shares (all the rays of an envmap), computed once instead
    // of once per ray: the origin in each level's index coordinates and, for axis-aligned
    // levels, the offsets from the origin to the level's faces in scene units along each axis
    // (a ray's slab test is then three products per level).
    struct RayOrigin {
        std::array<Vec3d, kMaxLevels> index;                  // entries [0, levels.size()) are set
        std::array<Vec3d, kMaxLevels> toLowFace, toHighFace;  // set for axis-aligned levels
    };
    RayOrigin rayOrigin(const Vec3d& world) const;
    int partitionRay(const RayOrigin& origin, const Vec3d& dir, Piece* pieces) const;
    int partitionRay(const Vec3d& origin, const Vec3d& dir, Piece* pieces) const {
        return partitionRay(rayOrigin(origin), dir, pieces);
    }
    // The same for any arrangement of levels (overlapping, disjoint): subtracts the intervals
    // finer levels claimed. partitionRay uses it unless every level lies inside the next
    // coarser one (the usual multiscale layout), where each level's interval minus the next
    // finer level's interval is at most two pieces and no subtraction or sort is needed.
    int partitionRayGeneral(const RayOrigin& origin, const Vec3d& dir, Piece* pieces) const;
    int partitionRayGeneral(const Vec3d& origin, const Vec3d& dir, Piece* pieces) const {
        return partitionRayGeneral(rayOrigin(origin), dir, pieces);
    }
    bool nestedLevels() const { return nested_; }

    // Field at a world point under finest-wins (for tests and reference checks).
    RenderSample sampleWorld(const Vec3d& world) const;
    // Edge length (cube root of the voxel volume) of the finest level containing a world
    // point; 0 outside every level.
    double voxelSizeAt(const Vec3d& world) const;

    // Boxes outside which the field is zero under finest-wins (render/medium_boxes.h): each
    // stored brick's box of occupied cells, less what finer levels' domains hide. Empty with
    // mediumBoxesValid() false if a level holding medium is not axis-aligned.
    const std::vector<MediumBox>& mediumBoxes() const { return mediumBoxes_; }
    bool mediumBoxesValid() const { return mediumBoxesValid_; }

    std::size_t storedBricks() const;
    std::size_t memoryBytes() const;

    // The radiance a surface of this scene typically has: the median, over lattice points with
    // density, of the brightest channel of their colour (emission / sigma); the mean if that
    // median is 0, and 0 only if every colour is black. The cell quadrature measures a piece's
    // possible error in units of it (ray_marcher.h), as the error of an envmap is judged
    // relative to its mean radiance.
    double typicalRadiance() const { return typicalRadiance_; }

private:
    bool nested_ = false;       // every level's box inside the next coarser level's box
    bool axisAligned_ = false;  // every level's axes are the world's (RenderLevel::axisAligned)
    double typicalRadiance_ = 0.0;
    std::vector<MediumBox> mediumBoxes_;
    bool mediumBoxesValid_ = false;
};

struct Piece {
    double t0, t1;  // scene units along the ray
    int level;
};

// Bound on bricks per level table (cells) and stored bricks overall.
constexpr std::size_t kMaxBrickCells = std::size_t(1) << 26;
constexpr std::size_t kMaxStoredBricks = std::size_t(1) << 18;  // ~3 GiB of lattice data

}  // namespace lh
