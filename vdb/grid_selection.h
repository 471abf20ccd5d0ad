// Which grids of a .vdb file a reader needs.
//
// A predicted volume's file also holds its MPI: 2 grids per plane (vdb/mpi.h), 64 for 32
// planes. Each plane is one voxel thick, so OpenVDB stores it in 8^3 leaves an eighth full:
// on the demo pair's prediction its 64 grids take 0.8 s and 160 MB to read, the 10 grids of
// the lighting volume 0.04 s and 30 MB. Commands that only render or inspect the volume skip
// them, and so does the trial read made for them (vdb/safe_read.h).
//
// Header-only: the trial-read program includes it without linking the vdb library.
#pragma once

#include <openvdb/io/File.h>

#include <string>

namespace lh {

enum class GridSelection {
    Every,           // every grid of the file
    LightingVolume,  // every grid but the MPI's planes
};

// The MPI's plane grids: `mpi_rgb_P<d>` and `mpi_alpha_P<d>` (vdb/mpi.h). No lighting volume
// grid can be named so (theirs start with density, color, Cd or colour).
inline bool isMpiPlaneGridName(const std::string& name) {
    return name.rfind("mpi_rgb", 0) == 0 || name.rfind("mpi_alpha", 0) == 0;
}

// The selected grids of an open file: all of them in file order, or the lighting volume's by
// name.
inline openvdb::GridPtrVec readSelectedGrids(openvdb::io::File& file, GridSelection which) {
    if (which == GridSelection::Every) return *file.getGrids();
    openvdb::GridPtrVec grids;
    for (auto name = file.beginName(); name != file.endName(); ++name)
        if (!isMpiPlaneGridName(*name)) grids.push_back(file.readGrid(*name));
    return grids;
}

}  // namespace lh
