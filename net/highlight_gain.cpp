#include "net/highlight_gain.h"

#include "core/errors.h"
#include "image/luminance.h"

#include <openvdb/tools/ValueTransformer.h>

namespace lh::net {

void validateHighlightGain(double gain) {
    if (!(gain >= 1.0 && gain <= kMaxHighlightGain))  // NaN too
        throw InputError("--highlight-gain must be in [1, " +
                         std::to_string(int(kMaxHighlightGain)) + "]");
}

void expandHighlights(LightingVolume& volume, double gain) {
    validateHighlightGain(gain);
    if (gain == 1.0) return;
    for (VolumeLevel& level : volume.levels) {
        openvdb::tools::foreach (level.color->beginValueOn(), [gain](const auto& voxel) {
            const openvdb::Vec3s c = *voxel;
            const double y = rec709Luminance(c.asPointer());
            if (!(y > kLampLuminance)) return;
            const double target = kLampLuminance + gain * (y - kLampLuminance);
            voxel.setValue(c * float(target / y));
        });
    }
}

}  // namespace lh::net
