// A checksum of what a grid holds, to tell whether a user edited it after `lighthouse export`.
//
// It covers the grid's active voxels with non-zero values: each one's index coordinate and
// the bits of its value (an active tile counts as each of its voxels). Those are what a
// renderer sees; what a program re-saving the file may change without an edit does not enter
// it: file and grid metadata, compression, the order of grids, inactive values, voxels versus
// tiles, and active voxels of value zero (as good as inactive). The per-voxel hashes are
// summed, so the result does not depend on the order the tree is visited in either.
#pragma once

#include <openvdb/openvdb.h>

#include <string>

namespace lh {

// How the manifest names the method (its "checksum" field), so that a later method is not
// compared with this one.
inline const char* const kGridChecksumMethod = "lighthouse-active-voxels-v1";

// 16 lower-case hex digits for a FloatGrid or a Vec3SGrid; "" for any other grid type.
std::string gridChecksum(const openvdb::GridBase& grid);

}  // namespace lh
