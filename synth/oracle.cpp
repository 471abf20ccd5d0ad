#include "synth/oracle.h"

#include <cmath>

namespace lh::synth {

LightingVolume oracleVolume(const Scene& scene, const RadianceField& field,
                            const VolumeLayout& layout, const OracleOptions& options) {
    LightingVolume volume = LightingVolume::fromLayout(layout);
    const int s = options.supersample;
    for (int k = 0; k < layout.levels; ++k) {
        const double voxel = layout.voxelSize(k);
        volume.fillLevel(k, [&](const Vec3d& centre) -> MediumSample {
            // Only voxels within reach of a surface can matter (half diagonal ~0.87 voxel).
            const double d = scene.distanceToSolid(centre);
            if (d > 0.87 * voxel || d < -1.5 * voxel) return {};
            int inside = 0;
            Vec3d radiance(0.0);
            for (int i = 0; i < s * s * s; ++i) {
                const Vec3d offset((i % s + 0.5) / s - 0.5, ((i / s) % s + 0.5) / s - 0.5,
                                   (i / (s * s) + 0.5) / s - 0.5);
                const Vec3d p = centre + offset * voxel;
                const int solid = scene.solidAt(p);
                if (solid < 0) continue;
                ++inside;
                radiance += field.radiance(nearestSurfacePoint(scene.primitives[solid], solid, p));
            }
            if (inside == 0) return {};
            const double fraction = double(inside) / (s * s * s);
            radiance /= double(inside);
            return {float(fraction * options.opacity / voxel),
                    openvdb::Vec3s(float(radiance.x()), float(radiance.y()), float(radiance.z()))};
        });
    }
    return volume;
}

}  // namespace lh::synth
