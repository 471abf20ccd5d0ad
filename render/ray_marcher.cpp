#include "render/ray_marcher.h"

#include "core/check.h"

#include "core/cpu_dispatch.h"
#include "core/errors.h"
#include "core/fast_exp.h"
#include "core/fast_log.h"

#include <cmath>

namespace lh {

void MarchOptions::validate() const {
    if (!(std::isfinite(stepVoxels) && stepVoxels >= 1e-4 && stepVoxels <= 64.0))
        throw InputError("step must be in [1e-4, 64] voxels, got " + std::to_string(stepVoxels));
    if (!(minTransmittance >= 0.0 && minTransmittance < 1.0))
        throw InputError("termination threshold must be in [0, 1), got " +
                         std::to_string(minTransmittance));
    if (!(maxStepOpticalDepth > 0.0))
        throw InputError("maximum optical depth per step must be positive, got " +
                         std::to_string(maxStepOpticalDepth));
    if (!(cellRefineBound > 0.0))
        throw InputError("refinement bound of the cell quadrature must be positive, got " +
                         std::to_string(cellRefineBound));
    if (!(surfaceTransmittance > 0.0 && surfaceTransmittance < 1.0))
        throw InputError("surface transmittance must be in (0, 1), got " +
                         std::to_string(surfaceTransmittance));
    if (cellNodes < 0 || cellNodes > 3)
        throw InputError("Gauss nodes per lattice cell must be 0 (fixed steps) or 1-3, got " +
                         std::to_string(cellNodes));
}

namespace {

constexpr double kSubdivideMinT = 1e-9;  // transmittance below which thick steps stay whole
constexpr int kMaxHalvings = 12;         // a cell piece is cut into at most 2^12 parts

// ln(x) for x >= 1: the optical depth from where the transmittance was x times the surface
// threshold to where it meets it. x is at most 2 for the usual threshold of 1/2.
inline double surfaceCrossing(double x) { return x <= 2.0 ? logOfOneToTwo(x) : std::log(x); }

// Adds one segment [t, t + dt] of constant medium `s` to the ray. Returns false once the
// transmittance is below minT, after crediting what is left of the ray with the segment's colour
// (ray_marcher.h, "Early stop"); records where it first falls below surfaceT.
inline bool addSegment(const RenderSample& s, double t, double dt, double minT, double surfaceT,
                       RayResult& r) {
    const double sigma = s.sigma, tau = sigma * dt;
    // E = exp(-tau) and weight = (1 - E) / sigma, stable for tiny sigma (-> dt) and huge
    // sigma (-> 1/sigma); one exp per segment, a series where 1 - E would cancel.
    double E, weight;
    if (tau < 1e-4) {
        E = 1.0 - tau * (1.0 - tau * (0.5 - tau / 6.0));
        weight = dt * (1.0 - tau * (0.5 - tau / 6.0));
    } else {
        E = expOfNegative(tau);
        weight = (1.0 - E) / sigma;
    }
    const double tw = r.transmittance * weight;
    r.radiance[0] += tw * s.emission[0];
    r.radiance[1] += tw * s.emission[1];
    r.radiance[2] += tw * s.emission[2];
    const double before = r.transmittance;
    r.transmittance *= E;
    // Crossing T = surfaceT inside this segment: once per ray, so one branch that is nearly never
    // taken (`&&` would branch on `before >= surfaceT` too, which flips once per ray, and
    // mispredict).
    if ((before >= surfaceT) & (r.transmittance < surfaceT))
        r.surfaceDistance = t + surfaceCrossing(before / surfaceT) / sigma;
    if (r.transmittance >= minT) return true;
    // The rest of the ray sees an opaque surface of this colour (emission / sigma).
    const double rest = r.transmittance / sigma;
    r.radiance[0] += rest * s.emission[0];
    r.radiance[1] += rest * s.emission[1];
    r.radiance[2] += rest * s.emission[2];
    r.transmittance = 0.0;
    return false;
}

// Integrates [t0, t1] in equal midpoint steps no longer than `stepT`, sub-dividing optically
// thick steps (ray_marcher.h). `sample(t)` returns the medium at ray parameter t.
// Returns false once the transmittance falls below the threshold.
template <class Sampler>
bool integrateSpan(const Sampler& sample, double t0, double t1, double stepT, const MarchOptions& o,
                   RayResult& r) {
    const double length = t1 - t0;
    if (length <= 0.0) return true;
    const int n = std::max(1, int(std::ceil(length / stepT - 1e-9)));
    const double dt = length / n;
    for (int i = 0; i < n; ++i) {
        const double start = t0 + i * dt;
        const RenderSample s = sample(start + 0.5 * dt);
        if (!(s.sigma > 0.f)) continue;
        const double tau = double(s.sigma) * dt;
        // Below kSubdivideMinT what follows cannot matter: do not pay for sub-steps there.
        if (tau <= o.maxStepOpticalDepth || r.transmittance < kSubdivideMinT) {
            if (!addSegment(s, start, dt, o.minTransmittance, o.surfaceTransmittance, r))
                return false;
            continue;
        }
        const int m = int(std::min<double>(kMaxSubsteps, std::ceil(tau / o.maxStepOpticalDepth)));
        const double sub = dt / m;
        for (int j = 0; j < m; ++j) {
            const double subStart = start + j * sub;
            const RenderSample ss = sample(subStart + 0.5 * sub);
            if (ss.sigma > 0.f &&
                !addSegment(ss, subStart, sub, o.minTransmittance, o.surfaceTransmittance, r))
                return false;
        }
    }
    return true;
}

// Gauss-Legendre rules on [0, 1]: a piece of length h is cut into sub-segments of length
// weight * h, each taking the medium at its node.
struct GaussRule {
    int count;
    double node[3], weight[3];
};
constexpr GaussRule kGaussRules[4] = {
    {0, {}, {}},
    {1, {0.5}, {1.0}},
    {2, {0.21132486540518713, 0.78867513459481287}, {0.5, 0.5}},
    {3, {0.11270166537925831, 0.5, 0.88729833462074169}, {5.0 / 18, 8.0 / 18, 5.0 / 18}},
};

// How a cell piece is integrated: the options, and 1 / RenderVolume::typicalRadiance (0 for
// a black scene, where nothing needs refining).
struct CellQuadrature {
    const MarchOptions& options;
    double perTypicalRadiance;
};

// Amanatides-Woo walk over a grid of `count` cells per axis, each `size` units wide (cell i
// spans [i size, (i + 1) size)), along u(t) = u0 + t qd; `inv` holds 1 / qd (infinite where a
// component is 0). One walk serves the bricks of a level (size 8) and the lattice cells of a
// brick (size 1).
struct GridWalk {
    int cell[3], step[3];
    double tNext[3];   // t at which the walk crosses the next plane along each axis
    double tDelta[3];  // t between two planes along each axis

    GridWalk(const Vec3d& u0, const Vec3d& qd, const Vec3d& inv, double t0, double size,
             const int count[3]) {
        for (int a = 0; a < 3; ++a) {
            // The cell holding u(t0), clamped to the grid. Truncating after the clamp is the
            // floor, without the libm call std::floor is on baseline x86-64 (no SSE4.1 round).
            const double u = (u0[a] + qd[a] * t0) * (1.0 / size);
            cell[a] = u > 0.0 ? int(std::min(u, double(count[a] - 1))) : 0;
            // Without branches (a walk is set up for every brick a ray enters): the next plane
            // is the cell's far side in the direction of travel; a parallel axis never has one
            // (|inv| is infinite there, and tNext is chosen, not computed, as 0 x inf is NaN).
            const bool forward = qd[a] > 0;
            step[a] = int(forward) - int(qd[a] < 0);
            const double tPlane = ((cell[a] + int(forward)) * size - u0[a]) * inv[a];
            tNext[a] = step[a] != 0 ? tPlane : std::numeric_limits<double>::infinity();
            tDelta[a] = size * std::abs(inv[a]);
        }
    }
    // Axis of the nearest plane, without branches (which the walks mispredict: the next axis
    // is irregular along a ray).
    int nearestAxis() const {
        const int a01 = tNext[1] < tNext[0];
        const double t01 = a01 ? tNext[1] : tNext[0];
        return tNext[2] < t01 ? 2 : a01;
    }
    // Crosses the plane along `axis`; false once the walk has left the grid (`count` cells
    // along that axis).
    bool advance(int axis, int count) {
        cell[axis] += step[axis];
        tNext[axis] += tDelta[axis];
        return unsigned(cell[axis]) < unsigned(count);
    }
};

// Integrates the part [ta, ta + h] of the ray inside one lattice cell with the Gauss rule of
// o.cellNodes (ray_marcher.h); `sample(t)` is the trilinear field of the cell. The nodes give
// the piece's optical depth exactly (sigma is cubic in t). A piece whose light may be
// misplaced by more than the bound is halved: where a ray meets a bright surface, the parts
// become short exactly where the density is, and stay exact in optical depth. The halving
// runs on a stack, front half first (a loop, not recursion, so that the whole marcher can be
// inlined into one function and compiled for the CPU it runs on: see marchRay). The part in
// hand stays in registers; only back halves wait on the stack.
//
// `Nodes` is o.cellNodes as a compile-time constant: the loops over the nodes unroll and the
// rule's nodes and weights become constants (marchRay picks the instance once per ray).
template <int Nodes, class Sampler>
bool integrateCellPiece(const Sampler& sample, double ta, double h, const CellQuadrature& cq,
                        RayResult& r) {
    static_assert(Nodes >= 1 && Nodes <= 3, "1-3 Gauss nodes per cell");
    const MarchOptions& o = cq.options;
    constexpr GaussRule rule = kGaussRules[Nodes];
    const double refineAbove = o.cellRefineBound * rule.count;
    struct Part {
        double start, length;
        int depth;  // halvings so far
    };
    Part pending[kMaxHalvings];  // depth first: at most one waiting back half per depth
    int waiting = 0;
    Part part{ta, h, 0};
    for (;;) {
        RenderSample atNode[3];
        double tau = 0.0;  // optical depth of the part
        for (int q = 0; q < rule.count; ++q) {
            atNode[q] = sample(part.start + part.length * rule.node[q]);
            tau += double(atNode[q].sigma) * rule.weight[q] * part.length;
        }
        // The sub-segments misplace light in proportion to the optical depth they see (tau T)
        // and to how bright it is: measured in typical radiances, the same bound holds the
        // error of an envmap relative to its mean radiance, and dim walls are not refined for
        // nothing. Below kSubdivideMinT what follows cannot matter: do not pay for halving there.
        if (part.depth < kMaxHalvings && r.transmittance >= kSubdivideMinT) {
            // Halve if tau T brightness / typical > refineAbove, where brightness is the
            // brightest colour channel (emission / sigma) over the nodes with density. Written
            // as one product per node, emission x scale > refineAbove x sigma: the same test
            // without a division (whose latency the whole loop otherwise waits on).
            const double scale = tau * r.transmittance * cq.perTypicalRadiance;
            bool misplacesTooMuch = false;
            for (int q = 0; q < rule.count; ++q) {
                const RenderSample& s = atNode[q];
                const float brightest = std::max({s.emission[0], s.emission[1], s.emission[2]});
                misplacesTooMuch |= (s.sigma > 0.f) & (brightest * scale > refineAbove * s.sigma);
            }
            if (misplacesTooMuch) {
                const double half = 0.5 * part.length;
                ++part.depth;
                LH_DCHECK(waiting < kMaxHalvings);
                pending[waiting++] = {part.start + half, half, part.depth};  // back half, later
                part.length = half;                                          // front half, now
                continue;
            }
        }
        double start = part.start;
        for (int q = 0; q < rule.count; ++q) {
            const double length = part.length * rule.weight[q];
            if (atNode[q].sigma > 0.f && !addSegment(atNode[q], start, length, o.minTransmittance,
                                                     o.surfaceTransmittance, r))
                return false;
            start += length;
        }
        if (waiting == 0) return true;
        part = pending[--waiting];
    }
}

// Walks the lattice cells of one brick crossed by [t0, t1] (a DDA at cell resolution) and
// integrates the occupied ones. `ub` is the ray origin in the brick's lattice coordinates.
template <int Nodes>
bool marchCells(const float* brick, const uint64_t* mask, const Vec3d& ub, const Vec3d& qd,
                const Vec3d& inv, double t0, double t1, const CellQuadrature& cq, RayResult& r) {
    constexpr int n = RenderLevel::kBrick;
    constexpr int kCells[3] = {n, n, n};
    GridWalk walk(ub, qd, inv, t0, 1.0, kCells);
    const int* cell = walk.cell;
    double t = t0;
    while (t < t1) {
        const int axis = walk.nearestAxis();
        const double tb = std::min(walk.tNext[axis], t1);
        if (tb > t && (mask[cell[2]] >> (cell[0] + n * cell[1]) & 1u)) {
            // The cell's lattice point (0, 0, 0), read in place: lookups inside one cell share
            // the address arithmetic and the cache lines.
            const float* corner = brick + cell[2] * RenderLevel::kLatticeZ +
                                  cell[1] * RenderLevel::kLatticeY + cell[0] * 4;
            const Vec3d base = ub - Vec3d(cell[0], cell[1], cell[2]);  // cell-local origin
            const auto sample = [&](double tt) {
                return RenderLevel::sampleCell(corner, float(base[0] + qd[0] * tt),
                                               float(base[1] + qd[1] * tt),
                                               float(base[2] + qd[2] * tt));
            };
            if (!integrateCellPiece<Nodes>(sample, t, tb - t, cq, r)) return false;
        }
        t = std::max(t, tb);
        if (!walk.advance(axis, n)) break;
    }
    return true;
}

// Narrows [ta, tb] to the part of the ray inside a brick's box of occupied cells
// (RenderLevel::cellBox); the field is zero outside it, so the narrowing loses nothing.
inline bool clipToCellBox(const RenderLevel::CellBox& box, const Vec3d& ub, const Vec3d& qd,
                          const Vec3d& inv, double& ta, double& tb) {
    const double lo[3] = {double(box.lo[0]), double(box.lo[1]), double(box.lo[2])};
    const double hi[3] = {double(box.hi[0]), double(box.hi[1]), double(box.hi[2])};
    return clipToBox(lo, hi, ub, qd, inv, ta, tb);
}

// Walks the 8^3 bricks of `level` crossed by [t0, t1] (Amanatides-Woo DDA) and integrates
// only the occupied ones, sampling each brick's lattice directly: with the cell quadrature of
// `Nodes` nodes, or (Nodes = 0) in fixed steps of stepT.
template <int Nodes>
bool marchSkipping(const RenderLevel& level, const LevelRay& ray, double t0, double t1,
                   double stepT, const CellQuadrature& cq, RayResult& r) {
    const MarchOptions& o = cq.options;
    constexpr double kBrick = RenderLevel::kBrick;
    const Vec3d& qd = ray.qd;
    const Vec3d u0 = ray.q0 - level.latticeOrigin.asVec3d();  // lattice coordinates of the origin
    // Only the part of the piece inside the level's occupied box holds medium; a level that
    // stores no brick holds none (its box is inverted, which the slab test would not notice).
    if (level.cellBoxes.empty() ||
        !clipToBox(level.occupiedLo.asPointer(), level.occupiedHi.asPointer(), u0, qd, ray.inv, t0,
                   t1))
        return true;
    const int* bricks = level.brickCount.data();
    GridWalk walk(u0, qd, ray.inv, t0, kBrick, bricks);
    const int* cell = walk.cell;
    double t = t0;
    while (t < t1) {
        const int axis = walk.nearestAxis();
        const double tExit = std::min(walk.tNext[axis], t1);
        if (tExit > t) {
            const int b = level.brickIndex(cell[0], cell[1], cell[2]);
            if (b >= 0) {
                const float* brick = level.brickPointer(b);
                // Ray in this brick's own lattice coordinates.
                const Vec3d ub = u0 - Vec3d(cell[0], cell[1], cell[2]) * kBrick;
                if constexpr (Nodes > 0) {
                    double ta = t, tb = tExit;
                    if (clipToCellBox(level.cellBox(b), ub, qd, ray.inv, ta, tb) &&
                        !marchCells<Nodes>(brick, level.cellMask(b), ub, qd, ray.inv, ta, tb, cq,
                                           r))
                        return false;
                } else {
                    const auto sample = [&](double tt) {
                        return RenderLevel::sampleLattice(brick, float(ub[0] + qd[0] * tt),
                                                          float(ub[1] + qd[1] * tt),
                                                          float(ub[2] + qd[2] * tt));
                    };
                    if (!integrateSpan(sample, t, tExit, stepT, o, r)) return false;
                }
            }
        }
        t = std::max(t, tExit);
        if (!walk.advance(axis, bricks[axis])) break;
    }
    return true;
}

}  // namespace

RayResult marchRay(const RenderVolume& volume, const Vec3d& origin, const Vec3d& dir,
                   const MarchOptions& options) {
    return marchRay(volume, volume.rayOrigin(origin), dir, options);
}

namespace {

// The march of one ray, its pieces in order, for a compile-time node count (0: fixed steps).
template <int Nodes>
RayResult marchPieces(const RenderVolume& volume, const RenderVolume::RayOrigin& origin,
                      const Vec3d& dir, const MarchOptions& options, double tStart) {
    RayResult result;
    Piece pieces[RenderVolume::kMaxPieces];
    const int count = volume.partitionRay(origin, dir, pieces);
    LH_DCHECK(count >= 0 && count <= RenderVolume::kMaxPieces);
    const double typical = volume.typicalRadiance();
    const CellQuadrature cq{options, typical > 0.0 ? 1.0 / typical : 0.0};
    for (int p = 0; p < count; ++p) {
        if (pieces[p].t1 <= tStart) continue;  // no medium before tStart
        pieces[p].t0 = std::max(pieces[p].t0, tStart);
        const RenderLevel& level = volume.levels[pieces[p].level];
        // Mapped per piece, not in the partition: most rays end before their coarser pieces.
        const LevelRay ray = level.rayFromIndexOrigin(origin.index[pieces[p].level], dir);
        bool keepGoing;
        if constexpr (Nodes > 0) {
            keepGoing =
                marchSkipping<Nodes>(level, ray, pieces[p].t0, pieces[p].t1, 0.0, cq, result);
        } else {
            // One step of stepVoxels voxels of this level along the ray, in scene units.
            const double stepT = options.stepVoxels / ray.qd.length();
            const auto sample = [&](double t) { return level.sample(ray.q0 + ray.qd * t); };
            keepGoing =
                options.skipEmptySpace
                    ? marchSkipping<0>(level, ray, pieces[p].t0, pieces[p].t1, stepT, cq, result)
                    : integrateSpan(sample, pieces[p].t0, pieces[p].t1, stepT, options, result);
        }
        if (!keepGoing) break;
    }
    return result;
}

}  // namespace

// The marcher, walk and quadrature inlined, is compiled for x86-64-v4, x86-64-v3 and the
// baseline (core/cpu_dispatch.h). Measured: v3 7.6% fewer instructions and ~7% less time per
// envmap than the baseline, v4 1-4.5% less time than v3 (docs/performance.md).
LH_PER_CPU_FLATTENED
RayResult marchRay(const RenderVolume& volume, const RenderVolume::RayOrigin& origin,
                   const Vec3d& dir, const MarchOptions& options, double tStart) {
    switch (options.cellNodes) {
        case 1:
            return marchPieces<1>(volume, origin, dir, options, tStart);
        case 2:
            return marchPieces<2>(volume, origin, dir, options, tStart);
        case 3:
            return marchPieces<3>(volume, origin, dir, options, tStart);
        default:
            return marchPieces<0>(volume, origin, dir, options, 0.0);  // fixed steps ignore tStart
    }
}

}  // namespace lh
