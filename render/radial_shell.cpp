#include "render/radial_shell.h"

#include "core/errors.h"
#include "render/ray_marcher.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace lh {

void RadialShellOptions::validate() const {
    if (!(halfWidthVoxels >= 0.5 && halfWidthVoxels <= 8.0))
        throw InputError("shell half-width must be in [0.5, 8] voxels, got " +
                         std::to_string(halfWidthVoxels));
    if (!(minAlpha >= 0.0 && minAlpha < 1.0))
        throw InputError("shell minimum alpha must be in [0, 1), got " + std::to_string(minAlpha));
    if (directionsPerFace < 8 || directionsPerFace > 2048)
        throw InputError("shell directions per cube face must be in [8, 2048], got " +
                         std::to_string(directionsPerFace));
}

Vec3d defaultShellCentre(const VolumeLayout& layout) {
    if (layout.levels == 1) return Vec3d(0.0);
    // Chosen on the synthetic test split among 0.05, 0.25 and 0.5 of level 1's depth.
    return Vec3d(0.0, 0.0, 0.25 * layout.side(1));
}

namespace {

// What the centre sees in one direction.
struct SeenFromCentre {
    float alpha = 0.f;                    // 1 - transmittance behind the volume; 0: nothing
    openvdb::Vec3s color{0.f, 0.f, 0.f};  // composite radiance (black behind the volume)
    float depth = 0.f;                    // where half of alpha is gathered, scene units
};

// Directions from the centre as the pixels of a cube map: face 2a + (negative) for the major
// axis a, N x N pixels per face.
class CubeView {
public:
    explicit CubeView(int n) : n_(n), seen_(6 * std::size_t(n) * n) {}
    int pixelCount() const { return int(seen_.size()); }

    int pixelOf(const Vec3d& dir) const {
        int a = 0;
        if (std::abs(dir.y()) > std::abs(dir[a])) a = 1;
        if (std::abs(dir.z()) > std::abs(dir[a])) a = 2;
        const double m = std::abs(dir[a]);
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        const int u = std::clamp(int((dir[b] / m + 1.0) * 0.5 * n_), 0, n_ - 1);
        const int v = std::clamp(int((dir[c] / m + 1.0) * 0.5 * n_), 0, n_ - 1);
        return ((2 * a + (dir[a] < 0.0)) * n_ + v) * n_ + u;
    }
    Vec3d directionOf(int pixel) const {
        const int u = pixel % n_, v = (pixel / n_) % n_, face = pixel / (n_ * n_);
        const int a = face / 2, b = (a + 1) % 3, c = (a + 2) % 3;
        Vec3d d(0.0);
        d[a] = (face % 2) ? -1.0 : 1.0;
        d[b] = (u + 0.5) * 2.0 / n_ - 1.0;
        d[c] = (v + 0.5) * 2.0 / n_ - 1.0;
        return d.unit();
    }
    SeenFromCentre& at(int pixel) { return seen_[pixel]; }
    const SeenFromCentre& seen(const Vec3d& dir) const { return seen_[pixelOf(dir)]; }

private:
    int n_;
    std::vector<SeenFromCentre> seen_;
};

CubeView lookFromCentre(const RenderVolume& source, const Vec3d& centre,
                        const RadialShellOptions& options) {
    CubeView view(options.directionsPerFace);
    const RenderVolume::RayOrigin origin = source.rayOrigin(centre);
    const MarchOptions whole;  // the renderer's defaults: RMSE below 1e-3 of the mean
    tbb::parallel_for(tbb::blocked_range<int>(0, view.pixelCount(), 256),
                      [&](const tbb::blocked_range<int>& range) {
                          for (int p = range.begin(); p != range.end(); ++p) {
                              const Vec3d dir = view.directionOf(p);
                              const RayResult seen = marchRay(source, origin, dir, whole);
                              const double alpha = 1.0 - seen.transmittance;
                              if (!(alpha >= options.minAlpha) || alpha <= 0.0) continue;
                              // Where the ray has gathered half of its alpha: on the medium even
                              // where it is spread over two surfaces (a mean depth would fall
                              // between them). The first march had to end to know alpha; this
                              // one stops where it crosses that depth, which it records first.
                              MarchOptions half = whole;
                              half.surfaceTransmittance = 1.0 - 0.5 * alpha;
                              half.minTransmittance = half.surfaceTransmittance;
                              const double depth =
                                  marchRay(source, origin, dir, half).surfaceDistance;
                              if (!std::isfinite(depth)) continue;
                              SeenFromCentre& s = view.at(p);
                              s.alpha = float(alpha);
                              s.depth = float(depth);
                              for (int c = 0; c < 3; ++c) s.color[c] = float(seen.radiance[c]);
                          }
                      });
    return view;
}

// The medium of one level at a voxel centre `p` (scene units) of the same layout.
MediumSample mediumAt(const VolumeLevel& level, const Vec3d& p) {
    const openvdb::Coord ijk = level.transform().worldToIndexCellCentered(p);
    MediumSample s;
    s.sigma = level.density->tree().getValue(ijk);
    s.color = level.color->tree().getValue(ijk);
    return s;
}

// `volume` without the medium `camera` sees: what the shell's centre collapses when the camera's
// view is kept.
LightingVolume outsideCameraView(const LightingVolume& volume, const PinholeCamera& camera) {
    LightingVolume rest = LightingVolume::fromLayout(*volume.layout);
    for (int k = 0; k < volume.layout->levels; ++k)
        rest.fillLevel(k, [&](const Vec3d& p) -> MediumSample {
            if (camera.projectIntoImage(p)) return {};
            return mediumAt(volume.levels[k], p);
        });
    return rest;
}

}  // namespace

bool keepsCameraView(const LightingVolume& volume, const RadialShellOptions& options) {
    return options.keepCameraView && volume.refCamera.has_value();
}

namespace {
// What one voxel of the layer lets through: a ray from anywhere stops in the layer. 1e-4 stops
// rays in half the depth that the 1e-2 of shells written before took, so envmaps render faster
// at the same scores (docs/network.md, "The shell").
constexpr double kLayerTransmittance = 1e-4;
constexpr double kOlderLayerTransmittance = 1e-2;

// The density (per scene unit) at which one voxel `voxelSize` wide lets `transmittance` through.
double densityLettingThrough(double transmittance, double voxelSize) {
    return -std::log(transmittance) / voxelSize;
}

bool withinOnePercent(double value, double target) {
    return std::abs(value - target) <= 0.01 * target;
}
}  // namespace

float shellLayerDensity(double voxelSize) {
    return float(densityLettingThrough(kLayerTransmittance, voxelSize));
}

bool looksLikeUnmarkedShell(const LightingVolume& volume) {
    if (!volume.layout) return false;
    const std::optional<PinholeCamera>& camera = volume.refCamera;
    bool anyLayerVoxel = false;
    const int levels = int(volume.levels.size());
    for (int k = 0; k < levels; ++k) {
        const VolumeLevel& level = volume.levels[k];
        const double voxel = level.transform().voxelSize()[0];
        const double layer = shellLayerDensity(voxel);
        const double olderLayer = densityLettingThrough(kOlderLayerTransmittance, voxel);
        for (auto it = level.density->cbeginValueOn(); it; ++it) {
            const Vec3d p = level.transform().indexToWorld(it.getCoord());
            // A finer level hides this voxel (an import may have filled it from that level),
            // and the camera's view was kept as predicted.
            if (k + 1 < levels && volume.layout->box(k + 1).contains(p)) continue;
            if (camera && camera->projectIntoImage(p)) continue;
            if (!withinOnePercent(*it, layer) && !withinOnePercent(*it, olderLayer)) return false;
            anyLayerVoxel = true;
        }
    }
    return anyLayerVoxel;
}

LightingVolume collapseToShell(const LightingVolume& volume, const Vec3d& centre,
                               const RadialShellOptions& options) {
    options.validate();
    if (!volume.layout)
        throw InputError(
            "collapsing into a shell needs a volume on the nested layout "
            "(a predicted volume); this one has no layout");
    const VolumeLayout& layout = *volume.layout;
    if (!centre.isFinite() || !layout.box(0).contains(centre)) {
        const WorldBox box = layout.box(0);
        char text[256];
        std::snprintf(text, sizeof text,
                      "the shell's centre (%g, %g, %g) lies outside the volume, whose level 0 "
                      "spans [%g, %g] x [%g, %g] x [%g, %g]; choose a point inside the room",
                      centre.x(), centre.y(), centre.z(), box.min.x(), box.max.x(), box.min.y(),
                      box.max.y(), box.min.z(), box.max.z());
        throw InputError(text);
    }

    // With the camera's view kept, the centre looks only at the medium that is collapsed.
    const PinholeCamera* keptView = keepsCameraView(volume, options) ? &*volume.refCamera : nullptr;
    const RenderVolume source(keptView ? outsideCameraView(volume, *keptView) : volume);
    const CubeView view = lookFromCentre(source, centre, options);
    LightingVolume shell = LightingVolume::fromLayout(layout);
    shell.refCamera = volume.refCamera;
    shell.shellCentre = centre;
    for (int k = 0; k < layout.levels; ++k) {
        const double voxel = layout.voxelSize(k);                  // scene units
        const double halfWidth = options.halfWidthVoxels * voxel;  // scene units
        const float opaqueSigma = shellLayerDensity(voxel);
        shell.fillLevel(k, [&](const Vec3d& p) -> MediumSample {
            if (keptView && keptView->projectIntoImage(p)) return mediumAt(volume.levels[k], p);
            const Vec3d offset = p - centre;
            const double r = offset.length();
            if (!(r > 0.0)) return {};
            const SeenFromCentre& s = view.seen(offset / r);
            if (!(s.alpha > 0.f) || r < s.depth - halfWidth) return {};
            // On the layer, or behind it and part of a skirt: a neighbouring voxel's direction
            // sees its surface farther out, so a depth edge seen from elsewhere shows a wall
            // instead of a hole.
            bool inLayer = r < s.depth + halfWidth;
            for (int n = 0; n < 27 && !inLayer; ++n) {
                if (n == 13) continue;  // the voxel itself
                const Vec3d q = offset + voxel * Vec3d(n % 3 - 1, (n / 3) % 3 - 1, n / 9 - 1);
                const SeenFromCentre& sn = view.seen(q.unit());
                inLayer = sn.alpha > 0.f && r < sn.depth;
            }
            if (!inLayer) return {};
            MediumSample out;
            out.sigma = opaqueSigma;
            out.color = s.color;
            return out;
        });
    }
    return shell;
}

}  // namespace lh
