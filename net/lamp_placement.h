// Where the emitter head put its lamps, scored against the truth: `lighthouse eval`'s lamps.csv
// and the line under its table, for models with an emitter head ("+emitters").
//
// A lamp the head places well may still be too dim to show in any envmap, so neither PSNR nor
// highlight recall can say whether the placing works. Seen from each test envmap's point, a
// lamp is instead scored by the angle from its direction to the nearest highlight pixel (lamp
// or window) of that envmap's ground truth (image/highlights.h degreesToNearestHighlight): 0
// when it lies in front of a true lamp or window. The same score serves data sets without a
// scene description (dev_cycles), since it needs only the true envmaps.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace lh::net {

// One lamp seen from one envmap's point.
struct LampPlacement {
    std::string example;
    std::size_t envmap = 0;
    std::size_t lamp = 0;
    double alpha = 0;    // the lamp's voxel opacity at its centre: how lit it is
    double degrees = 0;  // to the nearest true highlight; NaN when the envmap has none
};

// Angles within this many degrees count as placed: a lamp of a 1-2 m cell seen from 2-3 m.
constexpr double kLampPlacedDegrees = 20.0;

// lamps.csv: example, envmap, lamp, alpha, degrees_to_nearest_highlight.
std::string lampPlacementCsv(const std::vector<LampPlacement>& lamps);

// The Markdown paragraph under eval's table: how many lamp-envmap pairs, the median angle, the
// share within kLampPlacedDegrees, the median opacity. Empty for no lamps (a model without an
// emitter head).
std::string lampPlacementMarkdown(const std::vector<LampPlacement>& lamps);

}  // namespace lh::net
