// Points files (cli/cli_common.h readPointsFile: one "x y z" or "x,y,z" per line, '#'
// comments), read by insert --path, predict and render-envmap --points. A bad file must be
// refused with a FileError or InputError; every point read must be finite.
#include "cli/cli_common.h"
#include "core/errors.h"
#include "fuzz/fuzz_input.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = lh::fuzz::writeInput(data, size, "points.txt");
    try {
        for (const lh::Vec3d& p : lh::cli::readPointsFile(path))
            if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
                lh::fuzz::fail("a points file gave a non-finite point");
    } catch (const lh::Error&) {
    }
    return 0;
}
