#include "render/first_medium.h"

#include "core/cpu_dispatch.h"
#include "image/envmap_layout.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lh {

namespace {

using Footprint = FirstMediumMap::Footprint;

bool containsOrigin(const Footprint& b) {
    return b.lo[0] <= 0 && b.hi[0] >= 0 && b.lo[1] <= 0 && b.hi[1] >= 0 && b.lo[2] <= 0 &&
           b.hi[2] >= 0;
}

// atan2(y, x) within 1.2e-5 radians, modulo 2 pi (a degree-9 odd polynomial for atan on
// [0, 1]; worst error measured over 10^7 random points), at a fraction of the cost of libm's:
// footprints are widened by kAtanError, 8x that, so that they still hold every pixel.
constexpr double kAtanError = 1e-4;
double roughAtan2(double y, double x) {
    const double ax = std::abs(x), ay = std::abs(y);
    if (ax == 0.0 && ay == 0.0) return 0.0;
    const double a = std::min(ax, ay) / std::max(ax, ay), s = a * a;
    double r =
        a * (0.9998660 + s * (-0.3302995 + s * (0.1801410 + s * (-0.0851330 + s * 0.0208351))));
    if (ay > ax) r = 0.5 * M_PI - r;
    if (x < 0.0) r = M_PI - r;
    return y < 0.0 ? -r : r;
}

// Just below 1: t x kBelowOne rounded to float is below t (float rounding moves a value by at
// most 2^-24 of it), so a start never moves past the medium.
constexpr double kBelowOne = 1.0 - 1.0 / (1 << 22);

// The largest float not above t (the start must never move past the medium).
float roundedDown(double t) {
    const float f = float(t);
    return double(f) > t ? std::nextafter(f, 0.f) : f;
}

// Sets the rectangle of rows and columns of the width x height envmap whose rays may hit box
// `f` (lo, hi and nearest set, relative to the origin) and its nearest distance rounded down;
// false if no pixel's ray may.
bool placeOnEnvmap(Footprint& f, int width, int height) {
    const double rowsPerRadian = height / M_PI, columnsPerRadian = width / (2.0 * M_PI);
    // Polar angle phi = atan2(rho, u) of a point at height u = -y above the origin and
    // distance rho from the vertical axis: it falls as u rises, and rises with rho above the
    // origin (falls below). Over the box, u and rho lie in [uLo, uHi] and [rhoLo, rhoHi], so
    // the extremes are at these corners of that rectangle: a bound, not always attained.
    const double uLo = -f.hi[1], uHi = -f.lo[1];
    const double gapX = std::max({f.lo[0], -f.hi[0], 0.0}),
                 gapZ = std::max({f.lo[2], -f.hi[2], 0.0});
    const double farX = std::max(-f.lo[0], f.hi[0]), farZ = std::max(-f.lo[2], f.hi[2]);
    const double rhoLo = std::sqrt(gapX * gapX + gapZ * gapZ),
                 rhoHi = std::sqrt(farX * farX + farZ * farZ);
    const double phiLo = roughAtan2(uHi > 0.0 ? rhoLo : rhoHi, uHi) - kAtanError;
    const double phiHi = roughAtan2(uLo > 0.0 ? rhoHi : rhoLo, uLo) + kAtanError;
    f.rowLo = std::max(0, int(std::ceil(phiLo * rowsPerRadian - 0.5)));
    f.rowHi = std::min(height - 1, int(std::floor(phiHi * rowsPerRadian - 0.5)));
    // Azimuth theta = atan2(x, z): a box whose (x, z) rectangle holds the vertical axis is
    // seen at every azimuth; otherwise it spans less than pi, between two of its corners.
    f.columnLo = 0, f.columnHi = width - 1;
    if (gapX > 0.0 || gapZ > 0.0) {
        const double middle = roughAtan2(0.5 * (f.lo[0] + f.hi[0]), 0.5 * (f.lo[2] + f.hi[2]));
        double below = 0.0, above = 0.0;  // corners' azimuths relative to the middle's
        for (const double x : {f.lo[0], f.hi[0]})
            for (const double z : {f.lo[2], f.hi[2]}) {
                double d = roughAtan2(x, z) - middle;
                d = d > M_PI ? d - 2.0 * M_PI : d < -M_PI ? d + 2.0 * M_PI : d;
                below = std::min(below, d), above = std::max(above, d);
            }
        // Column c's azimuth is (c + 0.5) / columnsPerRadian - pi (envmap_layout.h).
        f.columnLo =
            int(std::ceil((middle + below - 2 * kAtanError + M_PI) * columnsPerRadian - 0.5));
        f.columnHi =
            int(std::floor((middle + above + 2 * kAtanError + M_PI) * columnsPerRadian - 0.5));
        if (f.columnHi - f.columnLo + 1 >= width) f.columnLo = 0, f.columnHi = width - 1;
        if (f.columnHi < 0) f.columnLo += width, f.columnHi += width;
        if (f.columnLo >= width) f.columnLo -= width, f.columnHi -= width;
    }
    f.nearestBelow = roundedDown(f.nearest);
    return f.rowLo <= f.rowHi && f.columnLo <= f.columnHi;
}

}  // namespace

FirstMediumMap::FirstMediumMap(const RenderVolume& volume, const Vec3d& origin, int width,
                               int height)
    : width_(width), height_(height) {
    // The volume's medium boxes (render/medium_boxes.h) relative to the origin, each with the
    // distance to its nearest point.
    std::vector<Footprint> boxes;
    boxes.reserve(volume.mediumBoxes().size());
    for (const MediumBox& m : volume.mediumBoxes()) {
        Footprint box{};
        double squared = 0.0;
        for (int a = 0; a < 3; ++a) {
            box.lo[a] = m.lo[a] - origin[a], box.hi[a] = m.hi[a] - origin[a];
            const double gap = std::max({box.lo[a], -box.hi[a], 0.0});
            squared += gap * gap;
        }
        box.nearest = std::sqrt(squared);
        boxes.push_back(box);
    }
    // The reciprocals of the renderer's per-row and per-column factors of a direction
    // (envmap.cpp): a direction's are (1/sinPhi 1/sinTheta, -1/cosPhi, 1/sinPhi 1/cosTheta).
    // They are finite for the layout's pixel centres; were one not, no ray would be skipped.
    perSinTheta_.resize(width), perCosTheta_.resize(width), perSinPhi_.resize(height),
        perCosPhi_.resize(height);
    for (int c = 0; c < width; ++c) {
        const double theta = envmapAzimuth(c + 0.5, width);
        perSinTheta_[c] = 1.0 / std::sin(theta), perCosTheta_[c] = 1.0 / std::cos(theta);
    }
    for (int r = 0; r < height; ++r) {
        const double phi = envmapPolarAngle(r + 0.5, height);
        perSinPhi_[r] = 1.0 / std::sin(phi), perCosPhi_[r] = -1.0 / std::cos(phi);  // y = -cos phi
    }
    const auto finite = [](const std::vector<double>& v) {
        return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
    };
    if (!volume.mediumBoxesValid() || std::any_of(boxes.begin(), boxes.end(), containsOrigin) ||
        !(finite(perSinTheta_) && finite(perCosTheta_) && finite(perSinPhi_) &&
          finite(perCosPhi_))) {
        skipNothing_ = true;
        return;
    }
    // Nearest boxes first: a pixel whose start is already no farther than a box's nearest point
    // cannot get a nearer one from it, which one comparison tells.
    std::sort(boxes.begin(), boxes.end(),
              [](const Footprint& a, const Footprint& b) { return a.nearest < b.nearest; });
    // Each box's rectangle of pixels, in parallel (the envmap's other core would otherwise wait
    // on this part), then the boxes that reach some pixel, still nearest first.
    std::vector<char> reaches(boxes.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, boxes.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i)
                              reaches[i] = placeOnEnvmap(boxes[i], width, height);
                      });
    for (std::size_t i = 0; i < boxes.size(); ++i)
        if (reaches[i]) footprints_.push_back(boxes[i]);
    // Per row, the footprints that reach it, nearest first (compressed rows: offsets, then
    // indices).
    rowStart_.assign(std::size_t(height) + 1, 0);
    for (const Footprint& f : footprints_)
        for (int r = f.rowLo; r <= f.rowHi; ++r) ++rowStart_[std::size_t(r) + 1];
    for (int r = 0; r < height; ++r) rowStart_[std::size_t(r) + 1] += rowStart_[r];
    rowFootprints_.resize(rowStart_.back());
    std::vector<std::size_t> filled(rowStart_.begin(), rowStart_.end() - 1);
    for (std::size_t i = 0; i < footprints_.size(); ++i)
        for (int r = footprints_[i].rowLo; r <= footprints_[i].rowHi; ++r)
            rowFootprints_[filled[r]++] = uint32_t(i);
}

LH_PER_CPU
void FirstMediumMap::fillRows(int rowBegin, int rowEnd, float* out) const {
    const int width = width_;
    if (skipNothing_) {
        std::fill(out, out + std::size_t(rowEnd - rowBegin) * width, 0.f);
        return;
    }
    constexpr float kInf = std::numeric_limits<float>::infinity();
    std::fill(out, out + std::size_t(rowEnd - rowBegin) * width, kInf);
    // The largest start in each block of kBlock pixels of the row: a box whose nearest point is
    // no nearer than that skips the whole block (far boxes, mostly hidden behind near ones).
    constexpr int kBlock = 16;
    const int blocksPerRow = (width + kBlock - 1) / kBlock;
    std::vector<float> rowBlockMax(blocksPerRow);
    for (int r = rowBegin; r < rowEnd; ++r) {
        float* row = out + std::size_t(r - rowBegin) * width;
        std::fill(rowBlockMax.begin(), rowBlockMax.end(), kInf);
        for (std::size_t i = rowStart_[r]; i < rowStart_[std::size_t(r) + 1]; ++i) {
            const Footprint& b = footprints_[rowFootprints_[i]];
            const float nearest = b.nearestBelow;  // skipping on it never loses a nearer entry
            // The slab of y is the same along a row (y = -cos phi): a row that misses it misses the
            // box.
            const double y0 = b.lo[1] * perCosPhi_[r], y1 = b.hi[1] * perCosPhi_[r];
            const double nearY = std::max(0.0, std::min(y0, y1)), farY = std::max(y0, y1);
            if (nearY > farY) continue;
            const int columnLo = b.columnLo, columnHi = b.columnHi;
            // The azimuth wraps around: [columnLo, columnHi] lies in [-width, 2 width) and is at
            // most width long, so it is at most two runs of [0, width).
            const int runs[3][2] = {
                {std::max(columnLo, 0), std::min(columnHi, width - 1)},
                {std::max(columnLo, -width) + width, std::min(columnHi, -1) + width},
                {std::max(columnLo, width) - width, std::min(columnHi, 2 * width - 1) - width}};
            for (const auto& run : runs)
                for (int block = run[0] / kBlock; run[0] <= run[1] && block <= run[1] / kBlock;
                     ++block) {
                    if (rowBlockMax[block] <= nearest) continue;  // nothing here can get nearer
                    const int first = std::max(run[0], block * kBlock),
                              last = std::min(run[1], block * kBlock + kBlock - 1);
                    // Branch-free, so that the compiler runs it on several pixels at once.
                    const double perSinPhi = perSinPhi_[r], loX = b.lo[0], hiX = b.hi[0],
                                 loZ = b.lo[2], hiZ = b.hi[2];
                    const double* perSinTheta = perSinTheta_.data();
                    const double* perCosTheta = perCosTheta_.data();
                    for (int c = first; c <= last; ++c) {
                        const double ix = perSinPhi * perSinTheta[c],
                                     iz = perSinPhi * perCosTheta[c];
                        const double x0 = loX * ix, x1 = hiX * ix, z0 = loZ * iz, z1 = hiZ * iz;
                        const double tNear =
                            std::max(nearY, std::max(std::min(x0, x1), std::min(z0, z1)));
                        const double tFar =
                            std::min(farY, std::min(std::max(x0, x1), std::max(z0, z1)));
                        const float below = float(tNear * kBelowOne), current = row[c];
                        const float entry = tNear <= tFar ? below : kInf;
                        row[c] = entry < current ? entry : current;
                    }
                    const int blockEnd = std::min(width, (block + 1) * kBlock);
                    rowBlockMax[block] = *std::max_element(row + block * kBlock, row + blockEnd);
                }
        }
    }
}

std::vector<float> FirstMediumMap::all() const {
    std::vector<float> starts(std::size_t(width_) * height_);
    fillRows(0, height_, starts.data());
    return starts;
}

}  // namespace lh
