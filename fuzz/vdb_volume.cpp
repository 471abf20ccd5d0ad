// .vdb files (vdb/volume_io.h loadVolumeFile), read as every command reads a volume: first by
// the exec'd probe (vdb/safe_read.h, lighthouse-vdb-probe, which the build puts beside this
// program), then in this process. A bad file must be refused with a FileError or InputError;
// a file that loads must give what the loader promises: NaN, Inf and negative values replaced
// (voxels, tiles and backgrounds), and an MPI, when there is one, that validates.
#include "core/errors.h"
#include "fuzz/fuzz_input.h"
#include "vdb/volume_io.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace {

bool usable(float v) { return std::isfinite(v) && v >= 0.f; }
bool usable(const openvdb::Vec3s& v) { return usable(v.x()) && usable(v.y()) && usable(v.z()); }

template <typename GridT>
void requireSanitised(const GridT& grid) {
    if (!usable(grid.background()))
        lh::fuzz::fail("grid '" + grid.getName() + "' kept a bad background");
    for (auto it = grid.cbeginValueAll(); it; ++it)
        if (!usable(*it))
            lh::fuzz::fail("grid '" + grid.getName() + "' kept a NaN, Inf or negative value");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = lh::fuzz::writeInput(data, size, "volume.vdb");
    try {
        std::vector<std::string> warnings;
        const lh::VolumeFile file = lh::loadVolumeFile(path, &warnings);
        for (const lh::VolumeLevel& level : file.volume.levels) {
            requireSanitised(*level.density);
            requireSanitised(*level.color);
        }
        if (file.mpi) {
            try {
                file.mpi->validate();
            } catch (const lh::Error& e) {
                lh::fuzz::fail(std::string("a loaded MPI does not validate: ") + e.what());
            }
        }
    } catch (const lh::Error&) {
    }
    return 0;
}
