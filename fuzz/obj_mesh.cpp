// OBJ meshes (insert/mesh.h loadMesh, tinyobjloader underneath), read by `insert --object`. A
// bad file must be refused with a FileError or InputError; a mesh that loads must be usable:
// finite unit-radius positions, unit normals, and indices that name existing vertices.
#include "core/errors.h"
#include "fuzz/fuzz_input.h"
#include "insert/mesh.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = lh::fuzz::writeInput(data, size, "mesh.obj");
    try {
        const lh::TriangleMesh mesh = lh::loadMesh(path);
        if (mesh.indices.size() % 3 != 0 || mesh.normals.size() != mesh.positions.size())
            lh::fuzz::fail("a loaded mesh has a partial triangle or a normal per vertex missing");
        for (std::uint32_t i : mesh.indices)
            if (i >= mesh.positions.size())
                lh::fuzz::fail("a loaded mesh names a vertex it does not have");
        for (const lh::Vec3d& p : mesh.positions)
            if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()) ||
                p.length() > 1.0 + 1e-6)
                lh::fuzz::fail(
                    "a loaded mesh has a vertex that is not finite or outside the unit sphere");
        for (const lh::Vec3d& n :
             mesh.normals)  // zero where every triangle at a vertex is degenerate
            if (!(n.length() == 0.0 || std::abs(n.length() - 1.0) < 1e-6))
                lh::fuzz::fail("a loaded mesh has a normal that is neither unit nor zero");
    } catch (const lh::Error&) {
    }
    return 0;
}
