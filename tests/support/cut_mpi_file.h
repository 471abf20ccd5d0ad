// A predicted volume's file whose MPI is damaged and whose lighting volume is not: for the
// tests of reading only the grids a command needs (vdb/grid_selection.h).
#pragma once

#include "vdb/example_volume.h"
#include "vdb/volume_io.h"

#include <filesystem>
#include <string>

namespace lh::test {

// Saves `volume` with a 3-plane MPI whose every pixel holds alpha 0.5, so that each plane grid
// has voxels to read.
inline void saveWithFilledMpi(const std::string& path, const LightingVolume& volume) {
    Mpi mpi = Mpi::create(exampleCameras().ref, 1.0, 7.0, 3);
    for (int d = 0; d < mpi.planeCount(); ++d)
        for (int y = 0; y < mpi.camera.height; ++y)
            for (int x = 0; x < mpi.camera.width; ++x) mpi.pixel(d, x, y)[3] = 0.5f;
    saveVdb(path, &volume, &mpi);
}

// Cuts 200 bytes off the end of a file saveWithFilledMpi wrote. saveVdb writes the MPI's planes
// after the volume's grids, so only the last plane's grid is damaged.
inline void cutShortInsideItsMpi(const std::string& path) {
    std::filesystem::resize_file(path, std::filesystem::file_size(path) - 200);
}

}  // namespace lh::test
