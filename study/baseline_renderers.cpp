#include "study/baseline_renderers.h"

#include "core/errors.h"
#include "image/envmap_layout.h"

#include <openvdb/tools/Interpolation.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace lh {

namespace {

struct Sphere {
    double radius;  // scene units
    double shell;   // thickness it stands for
    int level;
};

}  // namespace

ImageRGB renderEnvmapConcentricSpheres(const RenderVolume& volume, const Vec3d& position, int width,
                                       int height, int spheresPerLevel) {
    EnvmapOptions({width, height, MarchOptions{}}).validate();
    if (spheresPerLevel < 1) throw InputError("spheres per level must be positive");
    // Sphere radii per level: between the nearest and farthest point of the level's box.
    std::vector<Sphere> spheres;
    for (int k = 0; k < int(volume.levels.size()); ++k) {
        const RenderLevel& level = volume.levels[k];
        double nearest = 0, farthest = 0;
        const Vec3d q = level.toIndex(position);
        Vec3d closest;
        for (int a = 0; a < 3; ++a)
            closest[a] = std::clamp(q[a], level.domainLo[a], level.domainHi[a]);
        nearest = (level.indexToWorld * (closest - q)).length();
        for (int c = 0; c < 8; ++c) {
            const Vec3d corner((c & 1) ? level.domainHi.x() : level.domainLo.x(),
                               (c & 2) ? level.domainHi.y() : level.domainLo.y(),
                               (c & 4) ? level.domainHi.z() : level.domainLo.z());
            farthest = std::max(farthest, (level.indexToWorld * (corner - q)).length());
        }
        const double shell = (farthest - nearest) / spheresPerLevel;
        for (int i = 0; i < spheresPerLevel; ++i)
            spheres.push_back({nearest + (i + 0.5) * shell, shell, k});
    }
    std::sort(spheres.begin(), spheres.end(),
              [](const Sphere& a, const Sphere& b) { return a.radius < b.radius; });
    ImageRGB image(width, height);
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int r = rows.begin(); r != rows.end(); ++r)
            for (int c = 0; c < width; ++c) {
                const Vec3d d = envmapPixelDirection(r, c, width, height);
                double t = 1, rgb[3] = {0, 0, 0};
                for (const Sphere& s : spheres) {
                    const Vec3d p = position + d * s.radius;
                    const RenderLevel& level = volume.levels[s.level];
                    const Vec3d q = level.toIndex(p);
                    if (!level.containsIndex(q)) continue;
                    bool finer = false;  // coarser levels are zeroed where a finer one exists
                    for (std::size_t k = s.level + 1; k < volume.levels.size() && !finer; ++k)
                        finer = volume.levels[k].containsIndex(volume.levels[k].toIndex(p));
                    if (finer) continue;
                    const RenderSample m = level.sample(q);
                    if (m.sigma <= 0) continue;
                    const double alpha = -std::expm1(-double(m.sigma) * s.shell);
                    for (int i = 0; i < 3; ++i) rgb[i] += t * alpha * m.emission[i] / m.sigma;
                    t *= 1 - alpha;
                }
                for (int i = 0; i < 3; ++i) image.at(c, r)[i] = float(rgb[i]);
            }
    });
    return image;
}

ImageRGB renderEnvmapOpenVdbFixedStep(const LightingVolume& volume, const Vec3d& position,
                                      int width, int height, double stepVoxels) {
    EnvmapOptions({width, height, MarchOptions{stepVoxels, 1e-4, false, 0.5, 0}}).validate();
    // How far rays go: the farthest corner of any level.
    double reach = 0;
    for (const auto& level : volume.levels) {
        const WorldBox b = level.worldBounds();
        for (int c = 0; c < 8; ++c)
            reach = std::max(
                reach, (Vec3d((c & 1) ? b.max.x() : b.min.x(), (c & 2) ? b.max.y() : b.min.y(),
                              (c & 4) ? b.max.z() : b.min.z()) -
                        position)
                           .length());
    }
    std::vector<double> voxel;
    for (const auto& level : volume.levels) voxel.push_back(std::cbrt(level.voxelVolume()));
    ImageRGB image(width, height);
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        // Samplers (and their accessors) per task, never shared between threads.
        using DensitySampler = openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor,
                                                           openvdb::tools::BoxSampler>;
        using ColorSampler = openvdb::tools::GridSampler<openvdb::Vec3SGrid::ConstAccessor,
                                                         openvdb::tools::BoxSampler>;
        std::vector<openvdb::FloatGrid::ConstAccessor> densityAcc;
        std::vector<openvdb::Vec3SGrid::ConstAccessor> colorAcc;
        for (const auto& level : volume.levels) {
            densityAcc.push_back(level.density->getConstAccessor());
            colorAcc.push_back(level.color->getConstAccessor());
        }
        std::vector<DensitySampler> density;
        std::vector<ColorSampler> color;
        for (std::size_t k = 0; k < volume.levels.size(); ++k) {
            density.emplace_back(densityAcc[k], volume.levels[k].transform());
            color.emplace_back(colorAcc[k], volume.levels[k].transform());
        }
        for (int r = rows.begin(); r != rows.end(); ++r)
            for (int c = 0; c < width; ++c) {
                const Vec3d d = envmapPixelDirection(r, c, width, height);
                double t = 0, transmittance = 1, rgb[3] = {0, 0, 0};
                while (t < reach && transmittance > 1e-4) {
                    const Vec3d p = position + d * t;
                    int k = int(volume.levels.size()) - 1;
                    while (k >= 0 && !volume.levels[k].containsWorld(p)) --k;
                    const double dt = stepVoxels * (k >= 0 ? voxel[k] : voxel[0]);
                    if (k >= 0) {
                        const double sigma = density[k].wsSample(p);
                        if (sigma > 0) {
                            const openvdb::Vec3s col = color[k].wsSample(p);
                            const double alpha = -std::expm1(-sigma * dt);
                            for (int i = 0; i < 3; ++i) rgb[i] += transmittance * alpha * col[i];
                            transmittance *= 1 - alpha;
                        }
                    }
                    t += dt;
                }
                for (int i = 0; i < 3; ++i) image.at(c, r)[i] = float(rgb[i]);
            }
    });
    return image;
}

}  // namespace lh
