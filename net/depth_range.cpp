#include "net/depth_range.h"

#include "image/resample.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace lh::net {

namespace {

constexpr int kCandidates = 64;
constexpr double kMinDepth = 0.2, kMaxDepth = 100.0;  // scene units
constexpr int kWindowRadius = 3;                      // 7x7 aggregation window
constexpr int kMaxWidth = 192;                        // the sweep runs on a downsized pair

float grey(const ImageRGB& im, int x, int y) {
    const float* p = im.at(x, y);
    return (p[0] + p[1] + p[2]) / 3.f;
}

// Bilinear grey value at continuous pixel coordinates; NaN outside.
float sampleGrey(const ImageRGB& im, double px, double py) {
    const double fx = px - 0.5, fy = py - 0.5;
    if (fx < 0 || fy < 0 || fx > im.width - 1 || fy > im.height - 1)
        return std::numeric_limits<float>::quiet_NaN();
    const int x0 = std::min(int(fx), im.width - 2 < 0 ? 0 : im.width - 2);
    const int y0 = std::min(int(fy), im.height - 2 < 0 ? 0 : im.height - 2);
    const int x1 = std::min(x0 + 1, im.width - 1), y1 = std::min(y0 + 1, im.height - 1);
    const float ax = float(fx - x0), ay = float(fy - y0);
    return (grey(im, x0, y0) * (1 - ax) + grey(im, x1, y0) * ax) * (1 - ay) +
           (grey(im, x0, y1) * (1 - ax) + grey(im, x1, y1) * ax) * ay;
}

// Box sum over the window, via a summed-area table; NaN-free input expected.
std::vector<float> boxFilter(const std::vector<float>& v, int w, int h) {
    std::vector<double> sat(size_t(w + 1) * (h + 1), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            sat[size_t(y + 1) * (w + 1) + x + 1] =
                v[size_t(y) * w + x] + sat[size_t(y) * (w + 1) + x + 1] +
                sat[size_t(y + 1) * (w + 1) + x] - sat[size_t(y) * (w + 1) + x];
    std::vector<float> out(v.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int xa = std::max(0, x - kWindowRadius), xb = std::min(w, x + kWindowRadius + 1);
            const int ya = std::max(0, y - kWindowRadius), yb = std::min(h, y + kWindowRadius + 1);
            const double s = sat[size_t(yb) * (w + 1) + xb] - sat[size_t(ya) * (w + 1) + xb] -
                             sat[size_t(yb) * (w + 1) + xa] + sat[size_t(ya) * (w + 1) + xa];
            out[size_t(y) * w + x] = float(s / ((xb - xa) * (yb - ya)));
        }
    return out;
}

double percentile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5))];
}

}  // namespace

DepthRange estimateDepthRange(const ImageRGB& refFull, const ImageRGB& srcFull,
                              const PinholeCamera& refCamFull, const PinholeCamera& srcCamFull) {
    const int w = std::min(refFull.width, kMaxWidth);
    const int h = std::max(1, int(std::lround(double(refFull.height) * w / refFull.width)));
    const int ws = std::min(srcFull.width, kMaxWidth);
    const int hs = std::max(1, int(std::lround(double(srcFull.height) * ws / srcFull.width)));
    const ImageRGB ref = resizeImage(refFull, w, h), src = resizeImage(srcFull, ws, hs);
    const PinholeCamera refCam = refCamFull.resized(w, h), srcCam = srcCamFull.resized(ws, hs);

    // Texture: mean absolute gradient over the window; flat pixels cannot vote.
    std::vector<float> gradient(size_t(w) * h, 0.f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float gx = x + 1 < w ? std::abs(grey(ref, x + 1, y) - grey(ref, x, y)) : 0.f;
            const float gy = y + 1 < h ? std::abs(grey(ref, x, y + 1) - grey(ref, x, y)) : 0.f;
            gradient[size_t(y) * w + x] = gx + gy;
        }
    const std::vector<float> texture = boxFilter(gradient, w, h);

    // Per pixel: best aggregated cost over the candidates whose window lies in the source
    // image, and the mean over those same candidates. A pixel whose true match falls outside
    // the source image has only wrong candidates left, whose best cost is close to their mean.
    std::vector<float> bestCost(size_t(w) * h, std::numeric_limits<float>::infinity());
    std::vector<float> costSum(size_t(w) * h, 0.f);
    std::vector<int> validCount(size_t(w) * h, 0), bestIndex(size_t(w) * h, -1);
    std::vector<double> depths(kCandidates);
    for (int c = 0; c < kCandidates; ++c) {
        const double disparity =
            1.0 / kMaxDepth + (1.0 / kMinDepth - 1.0 / kMaxDepth) * c / (kCandidates - 1);
        depths[size_t(c)] = 1.0 / disparity;
        std::vector<float> cost(size_t(w) * h, 0.f), inside(size_t(w) * h, 0.f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const Vec3d camPoint = Vec3d((x + 0.5 - refCam.cx) / refCam.fx,
                                             (y + 0.5 - refCam.cy) / refCam.fy, 1.0) *
                                       depths[size_t(c)];
                const Vec3d world = refCam.rotation * camPoint + refCam.position;
                const Vec3d inSrc = srcCam.worldToCamera(world);
                if (inSrc.z() <= 1e-9) continue;
                const Vec3d pixel = srcCam.cameraToPixel(inSrc);
                const float value = sampleGrey(src, pixel.x(), pixel.y());
                if (std::isnan(value)) continue;
                cost[size_t(y) * w + x] = std::min(1.f, std::abs(value - grey(ref, x, y)));
                inside[size_t(y) * w + x] = 1.f;
            }
        const std::vector<float> aggregated = boxFilter(cost, w, h),
                                 coverage = boxFilter(inside, w, h);
        for (size_t i = 0; i < aggregated.size(); ++i) {
            if (coverage[i] < 0.999f) continue;  // the window leaves the source image
            ++validCount[i];
            costSum[i] += aggregated[i];
            if (aggregated[i] < bestCost[i]) {
                bestCost[i] = aggregated[i];
                bestIndex[i] = c;
            }
        }
    }

    std::vector<double> votes;
    for (size_t i = 0; i < bestCost.size(); ++i)
        if (texture[i] > 0.02f && validCount[i] >= kCandidates / 4 &&
            bestCost[i] < 0.3f * costSum[i] / float(validCount[i]))
            votes.push_back(depths[size_t(bestIndex[i])]);

    DepthRange range;
    range.votes = int(votes.size());
    if (votes.size() < std::max<size_t>(50, bestCost.size() / 100)) {
        range.near = kFallbackNear;
        range.far = kFallbackFar;
        range.fallback = true;
        return range;
    }
    range.near = std::max(kMinDepth, percentile(votes, 0.03) * 0.9);
    range.far = std::min(kMaxDepth, percentile(votes, 0.97) * 1.1);
    if (range.far <= range.near * 1.05) range.far = range.near * 1.05;
    return range;
}

}  // namespace lh::net
