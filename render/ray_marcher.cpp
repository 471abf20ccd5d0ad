#include "render/ray_marcher.h"

#include "core/errors.h"

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
}

namespace {

constexpr double kSubdivideMinT = 1e-9;  // transmittance below which thick steps stay whole

// Adds one segment [t, t + dt] of constant medium `s` to the ray. Returns false once the
// transmittance is below minT.
inline bool addSegment(const RenderSample& s, double t, double dt, double minT, RayResult& r) {
    const double sigma = s.sigma, tau = sigma * dt;
    // E = exp(-tau) and weight = (1 - E) / sigma, stable for tiny sigma (-> dt) and huge
    // sigma (-> 1/sigma); one exp per segment, a series where 1 - E would cancel.
    double E, weight;
    if (tau < 1e-4) {
        E = 1.0 - tau * (1.0 - tau * (0.5 - tau / 6.0));
        weight = dt * (1.0 - tau * (0.5 - tau / 6.0));
    } else {
        E = std::exp(-tau);
        weight = (1.0 - E) / sigma;
    }
    const double tw = r.transmittance * weight;
    r.radiance[0] += tw * s.emission[0];
    r.radiance[1] += tw * s.emission[1];
    r.radiance[2] += tw * s.emission[2];
    const double before = r.transmittance;
    r.transmittance *= E;
    if (before >= 0.5 && r.transmittance < 0.5)  // crossing inside this segment
        r.surfaceDistance = t + std::log(before / 0.5) / sigma;
    return r.transmittance >= minT;
}

// Integrates [t0, t1] in equal midpoint steps no longer than `stepT`, sub-dividing optically
// thick steps (ray_marcher.h). `sample(t)` returns the medium at ray parameter t.
// Returns false once the transmittance falls below the threshold.
template <class Sampler>
bool integrateSpan(const Sampler& sample, double t0, double t1, double stepT,
                   const MarchOptions& o, RayResult& r) {
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
            if (!addSegment(s, start, dt, o.minTransmittance, r)) return false;
            continue;
        }
        const int m = int(std::min<double>(kMaxSubsteps, std::ceil(tau / o.maxStepOpticalDepth)));
        const double sub = dt / m;
        for (int j = 0; j < m; ++j) {
            const double subStart = start + j * sub;
            const RenderSample ss = sample(subStart + 0.5 * sub);
            if (ss.sigma > 0.f && !addSegment(ss, subStart, sub, o.minTransmittance, r)) return false;
        }
    }
    return true;
}

// Walks the 8^3 bricks of `level` crossed by [t0, t1] (Amanatides-Woo DDA) and integrates
// only the occupied ones, sampling each brick's lattice directly.
bool marchSkipping(const RenderLevel& level, const Vec3d& q0, const Vec3d& qd, double t0,
                   double t1, double stepT, const MarchOptions& o, RayResult& r) {
    constexpr double kBrick = RenderLevel::kBrick;
    const Vec3d origin = level.latticeOrigin.asVec3d();
    const Vec3d u0 = q0 - origin;  // lattice coordinates of the ray origin
    // Brick-space ray: b(t) = (q0 - origin + t qd) / 8.
    const Vec3d b0 = u0 / kBrick, bd = qd / kBrick;
    const Vec3d start = b0 + bd * t0;
    int cell[3], step[3];
    double tNext[3], tDelta[3];
    for (int a = 0; a < 3; ++a) {
        cell[a] = std::clamp(int(std::floor(start[a])), 0, level.brickCount[a] - 1);
        if (bd[a] > 0) {
            step[a] = 1;
            tNext[a] = (cell[a] + 1 - b0[a]) / bd[a];
            tDelta[a] = 1.0 / bd[a];
        } else if (bd[a] < 0) {
            step[a] = -1;
            tNext[a] = (cell[a] - b0[a]) / bd[a];
            tDelta[a] = -1.0 / bd[a];
        } else {
            step[a] = 0;
            tNext[a] = tDelta[a] = std::numeric_limits<double>::infinity();
        }
    }
    double t = t0;
    while (t < t1) {
        const int axis = tNext[0] < tNext[1] ? (tNext[0] < tNext[2] ? 0 : 2)
                                             : (tNext[1] < tNext[2] ? 1 : 2);
        const double tExit = std::min(tNext[axis], t1);
        if (tExit > t) {
            const int b = level.brickIndex(cell[0], cell[1], cell[2]);
            if (b >= 0) {
                const float* brick = level.brickPointer(b);
                // Ray in this brick's own lattice coordinates.
                const Vec3d ub = u0 - Vec3d(cell[0], cell[1], cell[2]) * kBrick;
                const auto sample = [&](double tt) {
                    return RenderLevel::sampleLattice(brick, float(ub[0] + qd[0] * tt),
                                                      float(ub[1] + qd[1] * tt),
                                                      float(ub[2] + qd[2] * tt));
                };
                if (!integrateSpan(sample, t, tExit, stepT, o, r)) return false;
            }
        }
        t = std::max(t, tExit);
        cell[axis] += step[axis];
        tNext[axis] += tDelta[axis];
        if (cell[axis] < 0 || cell[axis] >= level.brickCount[axis]) break;
    }
    return true;
}

}  // namespace

RayResult marchRay(const RenderVolume& volume, const Vec3d& origin, const Vec3d& dir,
                   const MarchOptions& options) {
    RayResult result;
    Piece pieces[RenderVolume::kMaxPieces];
    const int count = volume.partitionRay(origin, dir, pieces);
    for (int p = 0; p < count; ++p) {
        const RenderLevel& level = volume.levels[pieces[p].level];
        const Vec3d q0 = level.toIndex(origin), qd = level.directionToIndex(dir);
        // One voxel of this level along the ray, in scene units.
        const double stepT = options.stepVoxels / qd.length();
        const auto sample = [&](double t) { return level.sample(q0 + qd * t); };
        const bool keepGoing =
            options.skipEmptySpace
                ? marchSkipping(level, q0, qd, pieces[p].t0, pieces[p].t1, stepT, options, result)
                : integrateSpan(sample, pieces[p].t0, pieces[p].t1, stepT, options, result);
        if (!keepGoing) break;
    }
    return result;
}

}  // namespace lh
