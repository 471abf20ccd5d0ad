// Where each ray of an envmap first meets the medium, found per envmap instead of walked by
// every ray.
//
// All the rays of an envmap leave one point. Before the first occupied cell a ray's walk is
// pure overhead (empty bricks, empty cells, the levels' pieces it crosses on the way). So the
// volume's medium boxes (render/medium_boxes.h: each stored brick's box of occupied cells in
// scene units, less what finer levels hide) are projected onto the envmap: the pixels whose
// rays may hit a box lie in a rectangle of rows (polar angles) and columns (azimuths), and for
// those the ray's entry into the box is computed exactly, several pixels at once. A pixel's
// start is the nearest entry; a ray that meets no box never meets medium (infinity). The field
// is zero outside the boxes, so the march from the start gives the answer it gives from the
// origin (up to rounding).
#pragma once

#include "render/render_volume.h"

#include <cstdint>
#include <vector>

namespace lh {

class FirstMediumMap {
public:
    // Prepares the boxes' footprints on the width x height envmap
    // (docs/conventions.md#envmap-layout) at `origin`. If the origin lies inside a box of occupied
    // cells, or a level's axes are not the world's, or a direction has a component of exactly 0,
    // every start is 0 (no skipping).
    FirstMediumMap(const RenderVolume& volume, const Vec3d& origin, int width, int height);

    // Starts of the pixels of rows [rowBegin, rowEnd), row-major into `out` (width floats per
    // row): a distance along the pixel's ray (scene units, rounded down to float) before which
    // the volume holds no medium; +inf if the ray never meets any. Rows are independent, so
    // bands of rows can be filled in parallel (renderEnvmap fills each band before marching it).
    void fillRows(int rowBegin, int rowEnd, float* out) const;

    // Every start of the envmap (for tests and tools).
    std::vector<float> all() const;

    int width() const { return width_; }
    int height() const { return height_; }

    // A box of occupied cells (scene units, relative to the origin) and the rectangle of
    // envmap pixels whose rays may hit it.
    struct Footprint {
        double lo[3], hi[3];
        double nearest;      // distance to the box's nearest point: no ray enters before it
        float nearestBelow;  // the same rounded down to float
        int rowLo, rowHi;    // rows whose polar angle may meet the box
        // Columns whose azimuth may meet it: columnLo in (-width, width), columnHi < 2 width
        // (the azimuth wraps around), at most width of them.
        int columnLo, columnHi;
    };

private:
    int width_, height_;
    bool skipNothing_ = false;           // every start is 0
    std::vector<Footprint> footprints_;  // nearest first
    // Row r is reached by footprints_[rowFootprints_[i]] for i in [rowStart_[r], rowStart_[r + 1]).
    std::vector<std::size_t> rowStart_;
    std::vector<uint32_t> rowFootprints_;
    // Reciprocals of the renderer's per-row and per-column factors of a direction (envmap.cpp).
    std::vector<double> perSinTheta_, perCosTheta_, perSinPhi_, perCosPhi_;
};

}  // namespace lh
