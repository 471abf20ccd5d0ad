// A multiplane image (MPI): D fronto-parallel RGB-alpha planes in the reference camera's
// frustum, spaced linearly in disparity between near and far
// (docs/conventions.md#multiplane-image). Plane alpha is an opacity, composited back to front. On
// disk every plane is a Vec3SGrid `mpi_rgb_P<d>` and a FloatGrid `mpi_alpha_P<d>` whose affine
// transform puts pixel (u, v) of that plane at its true place in the world frame, so any VDB tool
// shows the planes where they are.
#pragma once

#include "core/camera.h"

#include <openvdb/openvdb.h>

#include <vector>

namespace lh {

// Names of plane d's grids on disk: the stem followed by "_P" and d (two digits or more).
constexpr const char* kMpiRgbGridStem = "mpi_rgb";
constexpr const char* kMpiAlphaGridStem = "mpi_alpha";

struct Mpi {
    PinholeCamera camera;             // the reference camera the planes live in
    std::vector<double> planeDepths;  // depth of each plane, scene units, back (far) to front
    // Per plane, row-major, 4 floats per pixel: linear R, G, B and alpha in [0, 1].
    std::vector<std::vector<float>> planes;

    int planeCount() const { return int(planeDepths.size()); }
    float* pixel(int plane, int x, int y) {
        return &planes[plane][(std::size_t(y) * camera.width + x) * 4];
    }
    const float* pixel(int plane, int x, int y) const {
        return &planes[plane][(std::size_t(y) * camera.width + x) * 4];
    }

    // Allocates D planes, linear in disparity from far (plane 0) to near (plane D-1).
    static Mpi create(const PinholeCamera& camera, double nearDepth, double farDepth, int planes);
    // Throws InputError if sizes or depths are inconsistent.
    void validate() const;
};

// Depths linear in disparity: 1/far, ..., 1/near (back to front).
std::vector<double> disparityLinearDepths(double nearDepth, double farDepth, int count);

// Index -> world transform of plane `depth`: index (i, j, 0) is the centre of pixel (i, j)
// at that depth; index k steps along the optical axis by one lateral pixel footprint.
openvdb::math::Transform::Ptr mpiPlaneTransform(const PinholeCamera& camera, double depth);

// Grids for every plane (what volume_io writes) and back.
openvdb::GridPtrVec mpiToGrids(const Mpi& mpi);
Mpi mpiFromGrids(const openvdb::GridPtrVec& grids, const PinholeCamera& camera,
                 const std::string& sourceName);

}  // namespace lh
