// Highlights: do the lamps and windows of the truth show in a predicted envmap, and where?
//
// A mirror ball lit by an envmap shows its lamps and windows as highlights: the pixels a
// display shows white, whose luminance is above kLampLuminance (1, where an exposed photo
// clips). PSNR cannot say whether a prediction has them, since a lamp of 2 and one of 200 both
// display white, and the irradiance error says how much light there is, not where. These two
// numbers say where:
//   recall    = of the truth's highlight pixels, weighted by solid angle, the share that has a
//               predicted highlight pixel within `radius` of it (1: every lamp and window is
//               shown, near enough to where it is);
//   precision = of the prediction's highlight pixels, weighted alike, the share that has a true
//               highlight pixel within `radius` (1: no highlight where the room has none).
// A large window weighs more than a small lamp, as it does on a mirror ball.
#pragma once

#include "core/vec.h"
#include "image/image.h"

namespace lh {

// How far a predicted highlight may lie from the true one and still count, in degrees. On a
// mirror ball a reflected direction turns twice as fast as the surface normal, so 10 degrees
// moves a highlight near the ball's centre by about sin(5 deg) = 0.09 of its radius.
constexpr double kHighlightRadiusDegrees = 10.0;

struct HighlightMatch {
    double recall;     // NaN when the truth has no highlight pixel
    double precision;  // NaN when the prediction has none
};

// Pred and gt: equirectangular envmaps (docs/conventions.md#envmap-layout) of the same size,
// linear radiance, finite. Throws InputError for differing or empty sizes, or a radius outside
// (0, 180] degrees.
HighlightMatch matchHighlights(const ImageRGB& pred, const ImageRGB& gt,
                               double radiusDegrees = kHighlightRadiusDegrees);

// How far a direction points from the truth's nearest highlight pixel (a lamp or window, as
// above), in degrees: 0 when it points into one. It scores where a predictor placed a lamp,
// seen from the envmap's point, whether or not the lamp is bright enough to show. NaN when
// `gt` has no highlight pixel. Throws InputError for an empty envmap or a zero direction.
double degreesToNearestHighlight(const ImageRGB& gt, const Vec3d& direction);

}  // namespace lh
