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
}

namespace {

// Integrates [t0, t1] of one level in equal segments no longer than `stepT`.
// Returns false once the transmittance falls below the threshold.
bool integrateSpan(const RenderLevel& level, const Vec3d& q0, const Vec3d& qd, double t0,
                   double t1, double stepT, double minT, RayResult& r) {
    const double length = t1 - t0;
    if (length <= 0.0) return true;
    const int n = std::max(1, int(std::ceil(length / stepT - 1e-9)));
    const double dt = length / n;
    for (int i = 0; i < n; ++i) {
        const double t = t0 + (i + 0.5) * dt;
        const RenderSample s = level.sample(q0 + qd * t);
        if (s.sigma <= 0.f) continue;
        const double tau = double(s.sigma) * dt;
        // (1 - exp(-tau)) / sigma, stable for tiny sigma (-> dt) and huge sigma (-> 1/sigma).
        const double weight = tau > 1e-12 ? -std::expm1(-tau) / s.sigma : dt;
        for (int c = 0; c < 3; ++c) r.radiance[c] += r.transmittance * s.emission[c] * weight;
        const double before = r.transmittance;
        r.transmittance *= std::exp(-tau);
        if (before >= 0.5 && r.transmittance < 0.5)  // crossing inside this segment
            r.surfaceDistance = (t - 0.5 * dt) + std::log(before / 0.5) / s.sigma;
        if (r.transmittance < minT) return false;
    }
    return true;
}

// Walks the 8^3 bricks of `level` crossed by [t0, t1] (Amanatides-Woo DDA) and integrates
// only the occupied ones.
bool marchSkipping(const RenderLevel& level, const Vec3d& q0, const Vec3d& qd, double t0,
                   double t1, double stepT, double minT, RayResult& r) {
    constexpr double kBrick = RenderLevel::kBrick;
    const Vec3d origin = level.latticeOrigin.asVec3d();
    // Brick-space ray: b(t) = (q0 - origin + t qd) / 8.
    const Vec3d b0 = (q0 - origin) / kBrick, bd = qd / kBrick;
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
        if (tExit > t && level.brickOccupied(cell[0], cell[1], cell[2]) &&
            !integrateSpan(level, q0, qd, t, tExit, stepT, minT, r))
            return false;
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
        const bool keepGoing =
            options.skipEmptySpace
                ? marchSkipping(level, q0, qd, pieces[p].t0, pieces[p].t1, stepT,
                                options.minTransmittance, result)
                : integrateSpan(level, q0, qd, pieces[p].t0, pieces[p].t1, stepT,
                                options.minTransmittance, result);
        if (!keepGoing) break;
    }
    return result;
}

}  // namespace lh
