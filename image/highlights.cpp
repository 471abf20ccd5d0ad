#include "image/highlights.h"

#include "core/errors.h"
#include "image/envmap_layout.h"
#include "image/luminance.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace lh {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::uint8_t> highlightPixels(const ImageRGB& envmap) {
    std::vector<std::uint8_t> bright(std::size_t(envmap.width) * envmap.height);
    for (std::size_t p = 0; p < bright.size(); ++p)
        bright[p] = isLampOrWindow(&envmap.pixels[3 * p]);
    return bright;
}

// The unit direction of every pixel of a width x height envmap, row-major.
std::vector<Vec3d> pixelDirections(int width, int height) {
    std::vector<Vec3d> directions(std::size_t(width) * height);
    for (int r = 0; r < height; ++r)
        for (int c = 0; c < width; ++c)
            directions[std::size_t(r) * width + c] = envmapPixelDirection(r, c, width, height);
    return directions;
}

// Every pixel within `radius` (radians) of a marked pixel of `marks`: for each marked pixel,
// the rows a radius away at most, and in them the pixels whose direction is that close.
// `directions`: pixelDirections(width, height).
std::vector<std::uint8_t> dilateOnSphere(const std::vector<std::uint8_t>& marks,
                                         const std::vector<Vec3d>& directions, int width,
                                         int height, double radius) {
    const double cosRadius = std::cos(radius);
    // Pixel centres' polar angles differ by pi / H per row.
    const int rowReach = int(std::ceil(radius / (M_PI / height)));
    std::vector<std::uint8_t> near(marks.size(), 0);
    for (int r = 0; r < height; ++r)
        for (int c = 0; c < width; ++c) {
            const std::size_t p = std::size_t(r) * width + c;
            if (!marks[p]) continue;
            const Vec3d& d = directions[p];
            for (int rr = std::max(0, r - rowReach); rr <= std::min(height - 1, r + rowReach); ++rr)
                for (int cc = 0; cc < width; ++cc) {
                    const std::size_t q = std::size_t(rr) * width + cc;
                    if (!near[q] && d.dot(directions[q]) >= cosRadius) near[q] = 1;
                }
        }
    return near;
}

// Solid-angle share of the pixels of `of` that `covered` marks; NaN when `of` has none.
double coveredShare(const std::vector<std::uint8_t>& of, const std::vector<std::uint8_t>& covered,
                    int width, int height) {
    double total = 0.0, hit = 0.0;
    for (int r = 0; r < height; ++r) {
        const double solidAngle = std::sin(envmapPolarAngle(r + 0.5, height));  // up to a constant
        for (int c = 0; c < width; ++c) {
            const std::size_t p = std::size_t(r) * width + c;
            if (!of[p]) continue;
            total += solidAngle;
            if (covered[p]) hit += solidAngle;
        }
    }
    return total > 0.0 ? hit / total : kNaN;
}

}  // namespace

HighlightMatch matchHighlights(const ImageRGB& pred, const ImageRGB& gt, double radiusDegrees) {
    if (pred.width != gt.width || pred.height != gt.height || gt.width <= 0 || gt.height <= 0)
        throw InputError("highlights: the prediction is " + std::to_string(pred.width) + "x" +
                         std::to_string(pred.height) + " and the ground truth " +
                         std::to_string(gt.width) + "x" + std::to_string(gt.height) +
                         "; they must be the same non-empty size");
    if (!(radiusDegrees > 0.0 && radiusDegrees <= 180.0))
        throw InputError("highlights: the radius must be in (0, 180] degrees");
    const double radius = radiusDegrees * M_PI / 180.0;
    const int w = gt.width, h = gt.height;
    const std::vector<std::uint8_t> predBright = highlightPixels(pred),
                                    gtBright = highlightPixels(gt);
    const std::vector<Vec3d> directions = pixelDirections(w, h);
    return {coveredShare(gtBright, dilateOnSphere(predBright, directions, w, h, radius), w, h),
            coveredShare(predBright, dilateOnSphere(gtBright, directions, w, h, radius), w, h)};
}

double degreesToNearestHighlight(const ImageRGB& gt, const Vec3d& direction) {
    if (gt.width <= 0 || gt.height <= 0)
        throw InputError("highlights: the ground-truth envmap is empty");
    const double length = direction.length();
    if (!(length > 0.0) || !std::isfinite(length))
        throw InputError("highlights: the direction must be finite and non-zero");
    const Vec3d unit = direction / length;
    double bestCosine = -2.0;  // below any cosine: no highlight seen yet
    for (int r = 0; r < gt.height; ++r)
        for (int c = 0; c < gt.width; ++c)
            if (isLampOrWindow(gt.at(c, r)))
                bestCosine =
                    std::max(bestCosine, unit.dot(envmapPixelDirection(r, c, gt.width, gt.height)));
    if (bestCosine < -1.5) return kNaN;
    return std::acos(std::clamp(bestCosine, -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace lh
