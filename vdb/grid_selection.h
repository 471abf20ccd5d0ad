// Which grids of a .vdb file a reader needs.
//
// A predicted volume's file also holds its MPI: 2 grids per plane (vdb/mpi.h), 64 for 32
// planes. Each plane is one voxel thick, so OpenVDB stores it in 8^3 leaves an eighth full,
// and on the demo pair's prediction the trial read of every grid takes six times as long and
// four times the memory as that of the lighting volume's 10 (docs/format.md, "Only the grids
// a command needs"). Commands that only render or inspect the volume skip the MPI's grids,
// and so does the trial read made for them (vdb/safe_read.h).
//
// Header-only: the trial-read program includes it without linking the vdb library.
#pragma once

#include "vdb/mpi.h"

#include <openvdb/io/File.h>

#include <string>

namespace lh {

enum class GridSelection {
    Every,           // every grid of the file
    LightingVolume,  // every grid but the MPI's planes
};

// The MPI's plane grids, by the stems vdb/mpi.h names and reads them with. No lighting volume
// grid can be named so (theirs start with density, color, Cd or colour).
inline bool isMpiPlaneGridName(const std::string& name) {
    return name.rfind(kMpiRgbGridStem, 0) == 0 || name.rfind(kMpiAlphaGridStem, 0) == 0;
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
