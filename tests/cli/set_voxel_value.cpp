// A test tool: sets the first active value of a float or Vec3 grid of a .vdb file to VALUE
// (every component of a Vec3), keeping the file's other grids and metadata, as an edit in a
// DCC program might. The command-line tests use it to put NaN, Inf or negative values into an
// export, which the program itself never writes.
//   set_voxel_value FILE GRID VALUE       VALUE: a number, nan, inf or -inf
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: set_voxel_value FILE GRID VALUE\n");
        return 2;
    }
    const std::string path = argv[1], name = argv[2];
    const float value = std::strtof(argv[3], nullptr);  // strtof reads nan, inf and -inf
    openvdb::initialize();
    openvdb::GridPtrVecPtr grids;
    openvdb::MetaMap::Ptr meta;
    {
        openvdb::io::File file(path);
        file.open();
        grids = file.getGrids();
        meta = file.getMetadata();
        file.close();
    }
    bool set = false;
    for (const auto& grid : *grids) {
        if (grid->getName() != name) continue;
        if (auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(grid)) {
            if (auto it = f->beginValueOn()) it.setValue(value), set = true;
        } else if (auto v = openvdb::gridPtrCast<openvdb::Vec3SGrid>(grid)) {
            if (auto it = v->beginValueOn()) it.setValue(openvdb::Vec3s(value)), set = true;
        }
    }
    if (!set) {
        std::fprintf(stderr,
                     "set_voxel_value: '%s' has no float or Vec3 grid '%s' with an active value\n",
                     path.c_str(), name.c_str());
        return 1;
    }
    openvdb::io::File(path).write(*grids, *meta);
    return 0;
}
