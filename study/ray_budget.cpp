#include "study/ray_budget.h"

#include "core/errors.h"
#include "image/envmap_layout.h"
#include "render/free_space.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace lh {

void RayBudgetOptions::validate() const {
    if (points < 1 || points > 1000) throw InputError("ray budget: points must be in [1, 1000]");
    if (width < 2 || height < 1 || width != 2 * height || (long long)width * height > (1 << 22))
        throw InputError("ray budget: envmap size must be W x H with W = 2 H, at most 2^22 rays");
    if (!(minTransmittance > 0.0 && minTransmittance < 1.0))
        throw InputError("ray budget: the termination threshold must be in (0, 1)");
    if (!(stepVoxels >= 0.01 && stepVoxels <= 4.0))
        throw InputError("ray budget: the step must be in [0.01, 4] voxels");
}

double RayBudgetLevel::mediumVoxelsTotal() const {
    double sum = 0;
    for (double v : mediumVoxels) sum += v;
    return sum;
}

double RayBudget::mediumVoxelsPerRay() const {
    double sum = 0;
    for (const RayBudgetLevel& l : levels) sum += l.mediumVoxelsTotal();
    return sum;
}

namespace {

// Sums over the rays of one point (later over all), per level.
struct LevelTally {
    double reaching = 0;
    std::array<double, kAlphaClasses> voxels{};
    double light = 0;  // sum of RGB radiance
};
struct Tally {
    std::vector<LevelTally> levels;
    double stopped = 0;
    std::array<double, kLeftClasses> leaving{};  // rays leaving, by the class of what is left
};

int alphaClass(double alpha) {
    for (int c = 1; c < kAlphaClasses; ++c)
        if (alpha < kAlphaClassEdges[c]) return c - 1;
    return kAlphaClasses - 1;
}

// Marches one ray in midpoint steps of o.stepVoxels of each level, as the cell quadrature
// would meet the medium, adding what it crossed and gathered to `tally`.
void traceRay(const RenderVolume& volume, const std::vector<double>& voxelSizes,
              const Vec3d& origin, const Vec3d& dir, const RayBudgetOptions& o, Tally& tally) {
    Piece pieces[RenderVolume::kMaxPieces];
    const int count = volume.partitionRay(origin, dir, pieces);
    std::array<bool, RenderVolume::kMaxLevels> reached{};  // no allocation per ray
    double T = 1.0;
    for (int p = 0; p < count && T >= o.minTransmittance; ++p) {
        const int k = pieces[p].level;
        const RenderLevel& level = volume.levels[std::size_t(k)];
        const LevelRay ray = level.ray(origin, dir);
        const double stepT = o.stepVoxels / ray.qd.length();  // scene units
        const double length = pieces[p].t1 - pieces[p].t0;
        if (!(length > 0.0)) continue;
        LevelTally& lt = tally.levels[std::size_t(k)];
        if (!reached[std::size_t(k)]) lt.reaching += 1.0;
        reached[std::size_t(k)] = true;
        const int n = std::max(1, int(std::ceil(length / stepT)));
        const double dt = length / n, dtVoxels = dt * ray.qd.length();
        for (int i = 0; i < n && T >= o.minTransmittance; ++i) {
            const double t = pieces[p].t0 + (i + 0.5) * dt;
            const RenderSample s = level.sample(ray.q0 + ray.qd * t);
            if (!(s.sigma > 0.f)) continue;
            const double alpha = 1.0 - std::exp(-double(s.sigma) * voxelSizes[std::size_t(k)]);
            lt.voxels[std::size_t(alphaClass(alpha))] += dtVoxels;
            const double E = std::exp(-double(s.sigma) * dt);
            lt.light += T * (1.0 - E) / s.sigma * (s.emission[0] + s.emission[1] + s.emission[2]);
            T *= E;
        }
    }
    if (T < o.minTransmittance) {
        tally.stopped += 1.0;
        return;
    }
    int leftClass = 0;
    while (leftClass < kLeftClasses - 1 && T >= kLeftEdges[std::size_t(leftClass) + 1]) ++leftClass;
    tally.leaving[std::size_t(leftClass)] += 1.0;
}

}  // namespace

RayBudget measureRayBudget(const RenderVolume& volume, const RayBudgetOptions& o) {
    o.validate();
    return measureRayBudget(volume, freeSpacePoints(volume, o.points, o.seed), o);
}

RayBudget measureRayBudget(const RenderVolume& volume, const std::vector<Vec3d>& points,
                           const RayBudgetOptions& o) {
    o.validate();
    const std::size_t levelCount = volume.levels.size();
    std::vector<double> voxelSizes;
    for (const RenderLevel& l : volume.levels) voxelSizes.push_back(std::cbrt(l.voxelVolume));
    std::vector<Tally> perPoint(points.size(), Tally{std::vector<LevelTally>(levelCount), 0});
    // One task per point; the sums are then added in point order (deterministic).
    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t i) {
        for (int r = 0; r < o.height; ++r)
            for (int c = 0; c < o.width; ++c)
                traceRay(volume, voxelSizes, points[i],
                         envmapPixelDirection(r, c, o.width, o.height), o, perPoint[i]);
    });
    Tally all{std::vector<LevelTally>(levelCount), 0};
    for (const Tally& t : perPoint) {
        all.stopped += t.stopped;
        for (std::size_t c = 0; c < all.leaving.size(); ++c) all.leaving[c] += t.leaving[c];
        for (std::size_t k = 0; k < levelCount; ++k) {
            all.levels[k].reaching += t.levels[k].reaching;
            all.levels[k].light += t.levels[k].light;
            for (int c = 0; c < kAlphaClasses; ++c)
                all.levels[k].voxels[std::size_t(c)] += t.levels[k].voxels[std::size_t(c)];
        }
    }
    RayBudget budget;
    budget.points = int(points.size());
    budget.rays = budget.points * o.width * o.height;
    const double rays = budget.rays;
    double light = 0;
    for (const LevelTally& l : all.levels) light += l.light;
    budget.raysStopped = all.stopped / rays;
    for (std::size_t c = 0; c < all.leaving.size(); ++c)
        budget.raysLeaving[c] = all.leaving[c] / rays;
    for (std::size_t k = 0; k < levelCount; ++k) {
        RayBudgetLevel level;
        level.voxelSize = voxelSizes[k];
        level.raysReaching = all.levels[k].reaching / rays;
        for (int c = 0; c < kAlphaClasses; ++c)
            level.mediumVoxels[std::size_t(c)] = all.levels[k].voxels[std::size_t(c)] / rays;
        level.lightShare = light > 0 ? all.levels[k].light / light : 0.0;
        budget.levels.push_back(level);
    }
    return budget;
}

std::string rayBudgetMarkdown(const RayBudget& b, const RayBudgetOptions& o) {
    std::ostringstream md;
    char line[512];
    std::snprintf(line, sizeof line,
                  "\n## Where the rays go\n\n%d rays (%d points, %dx%d each), counted until their "
                  "transmittance falls below %g; medium voxels crossed per ray, by the alpha of "
                  "one voxel of the level crossed:\n\n",
                  b.rays, b.points, o.width, o.height, o.minTransmittance);
    md << line;
    md << "| level | voxel size | rays reaching | alpha < 0.03 | 0.03-0.15 | 0.15-0.5 | 0.5-0.9 | "
          ">= 0.9 | all | light share |\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t k = 0; k < b.levels.size(); ++k) {
        const RayBudgetLevel& l = b.levels[k];
        std::snprintf(
            line, sizeof line,
            "| %zu | %.4g | %.0f%% | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f%% |\n", k,
            l.voxelSize, 100 * l.raysReaching, l.mediumVoxels[0], l.mediumVoxels[1],
            l.mediumVoxels[2], l.mediumVoxels[3], l.mediumVoxels[4], l.mediumVoxelsTotal(),
            100 * l.lightShare);
        md << line;
    }
    std::snprintf(line, sizeof line,
                  "\n%.1f voxels of medium per ray in all; %.0f%% of the rays stop (the rest leave "
                  "the volume still transparent enough to count).\n",
                  b.mediumVoxelsPerRay(), 100 * b.raysStopped);
    md << line;
    // The rays that leave, by how much they keep: a prior that nearly closes the room leaves
    // most of them in the first class.
    md << "Rays that leave, by the transmittance they keep:";
    for (int c = 0; c < kLeftClasses; ++c) {
        const double lo = kLeftEdges[std::size_t(c)], hi = kLeftEdges[std::size_t(c) + 1];
        if (c == 0)  // from the threshold up: named by its upper edge
            std::snprintf(line, sizeof line, " %.0f%% below %g", 100 * b.raysLeaving[0], hi);
        else if (c == kLeftClasses - 1)  // up to 1: named by its lower edge
            std::snprintf(line, sizeof line, " %.0f%% above %g", 100 * b.raysLeaving[c], lo);
        else
            std::snprintf(line, sizeof line, " %.0f%% %g-%g", 100 * b.raysLeaving[c], lo, hi);
        md << line << (c + 1 < kLeftClasses ? "," : ".\n");
    }
    return md.str();
}

}  // namespace lh
