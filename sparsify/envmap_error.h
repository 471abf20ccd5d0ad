// How far the envmaps of a changed volume (pruned, or read back from a half-precision file)
// are from a reference set rendered at the same points: what the bound search of `sparsify`
// decides on, and what the studies of study/ report.
#pragma once

#include "image/image.h"
#include "render/ray_marcher.h"
#include "vdb/lighting_volume.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lh {

struct EnvmapSetError {
    double psnr = 100;        // dB, mean over the pairs (identical images count as 100)
    double relativeRmse = 0;  // RMSE of linear radiance over every pixel / mean reference radiance
};

// images[i] against reference[i]; both sets the same length and sizes.
EnvmapSetError compareEnvmapSets(const std::vector<ImageRGB>& images,
                                 const std::vector<ImageRGB>& reference);

// One width x height envmap per point, in order. With msPerEnvmap, the mean wall time of one
// envmap (ms) is written there.
std::vector<ImageRGB> renderEnvmapsAt(const RenderVolume& volume, const std::vector<Vec3d>& points,
                                      int width, int height, double* msPerEnvmap = nullptr,
                                      const MarchOptions& march = {});

// A directory for trial files, created: `requested`, or when that is empty a fresh one under
// the system's temporary directory (named after the process). The caller removes it.
std::string scratchDirectory(const std::string& requested);

// The volume as a file stores it: written Blosc-compressed into `scratch` (as half floats when
// `half`, rounded to `mantissaBits` when that is not 0; vdb/sparsity.h saveSparseVolume), read
// back, and the file removed. With `bytes`, the file's size is written there.
LightingVolume asStored(const LightingVolume& volume, bool half, const std::string& scratch,
                        uint64_t* bytes, int mantissaBits = 0);

}  // namespace lh
