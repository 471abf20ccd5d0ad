#include "vdb/mpi.h"

#include "core/errors.h"
#include "vdb/lighting_volume.h"

#include <cmath>
#include <map>
#include <sstream>

namespace lh {

namespace {
std::string planeSuffix(int d) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "_P%02d", d);
    return buf;
}
}  // namespace

std::vector<double> disparityLinearDepths(double nearDepth, double farDepth, int count) {
    if (!(nearDepth > 0 && farDepth >= nearDepth && std::isfinite(farDepth)))
        throw InputError("MPI depth range must satisfy 0 < near <= far < inf");
    if (count < 1 || count > 1024) throw InputError("MPI plane count must be in [1, 1024]");
    std::vector<double> depths(count);
    for (int d = 0; d < count; ++d) {
        const double t = count == 1 ? 1.0 : double(d) / (count - 1);
        const double disparity = (1.0 - t) / farDepth + t / nearDepth;
        depths[d] = 1.0 / disparity;
    }
    return depths;
}

Mpi Mpi::create(const PinholeCamera& camera, double nearDepth, double farDepth, int planes) {
    camera.validate("MPI camera");
    Mpi mpi;
    mpi.camera = camera;
    mpi.planeDepths = disparityLinearDepths(nearDepth, farDepth, planes);
    mpi.planes.assign(planes,
                      std::vector<float>(std::size_t(camera.width) * camera.height * 4, 0.f));
    return mpi;
}

void Mpi::validate() const {
    camera.validate("MPI camera");
    if (planeDepths.empty()) throw InputError("MPI has no planes");
    if (planes.size() != planeDepths.size()) throw InputError("MPI plane count mismatch");
    for (std::size_t d = 0; d < planes.size(); ++d) {
        if (!(planeDepths[d] > 0) || !std::isfinite(planeDepths[d]))
            throw InputError("MPI plane " + std::to_string(d) + " has a non-positive depth");
        if (planes[d].size() != std::size_t(camera.width) * camera.height * 4)
            throw InputError("MPI plane " + std::to_string(d) + " does not match the camera size");
    }
}

openvdb::math::Transform::Ptr mpiPlaneTransform(const PinholeCamera& camera, double depth) {
    // Camera-frame position of index (i, j, k):
    //   ((i + 0.5 - cx) z / fx, (j + 0.5 - cy) z / fy, z + k z / fx).
    // World = R * cam + position. OpenVDB matrices act on row vectors (world = [i j k 1] M),
    // so row r of M is the world image of index axis r and row 3 the image of the origin.
    const double ax = depth / camera.fx, ay = depth / camera.fy;
    const Vec3d axisI = camera.rotation * Vec3d(ax, 0, 0);
    const Vec3d axisJ = camera.rotation * Vec3d(0, ay, 0);
    const Vec3d axisK = camera.rotation * Vec3d(0, 0, ax);
    const Vec3d origin =
        camera.rotation * Vec3d((0.5 - camera.cx) * ax, (0.5 - camera.cy) * ay, depth) +
        camera.position;
    openvdb::math::Mat4d m(axisI.x(), axisI.y(), axisI.z(), 0.0,  //
                           axisJ.x(), axisJ.y(), axisJ.z(), 0.0,  //
                           axisK.x(), axisK.y(), axisK.z(), 0.0,  //
                           origin.x(), origin.y(), origin.z(), 1.0);
    try {
        return openvdb::math::Transform::createLinearTransform(m);
    } catch (const openvdb::ArithmeticError&) {
        // OpenVDB says "nearly singular matrix": the plane's voxels (depth / fx wide) are too
        // small to invert, which only an absurd depth range does.
        std::ostringstream why;
        why << "an MPI plane at depth " << depth << " m has voxels " << ax
            << " m wide, too small for OpenVDB: the cameras' near depth is implausibly small "
               "(near and far in cameras.json are depths in metres, e.g. 0.5 and 20; "
               "without them predict estimates them from the pair)";
        throw InputError(why.str());
    }
}

openvdb::GridPtrVec mpiToGrids(const Mpi& mpi) {
    mpi.validate();
    openvdb::GridPtrVec grids;
    const int w = mpi.camera.width, h = mpi.camera.height;
    for (int d = 0; d < mpi.planeCount(); ++d) {
        auto rgb = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
        auto alpha = openvdb::FloatGrid::create(0.f);
        auto xf = mpiPlaneTransform(mpi.camera, mpi.planeDepths[d]);
        rgb->setTransform(xf);
        alpha->setTransform(xf->copy());
        auto rgbAcc = rgb->getAccessor();
        auto alphaAcc = alpha->getAccessor();
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float* p = mpi.pixel(d, x, y);
                const openvdb::Coord ijk(x, y, 0);
                if (p[3] != 0.f) alphaAcc.setValue(ijk, p[3]);
                if (p[0] != 0.f || p[1] != 0.f || p[2] != 0.f)
                    rgbAcc.setValue(ijk, openvdb::Vec3s(p[0], p[1], p[2]));
            }
        rgb->setName(kMpiRgbGridStem + planeSuffix(d));
        alpha->setName(kMpiAlphaGridStem + planeSuffix(d));
        rgb->setVectorType(openvdb::VEC_INVARIANT);
        for (openvdb::GridBase::Ptr g :
             {openvdb::GridBase::Ptr(rgb), openvdb::GridBase::Ptr(alpha)}) {
            g->insertMeta("mpi_plane", openvdb::Int32Metadata(d));
            g->insertMeta("mpi_depth", openvdb::DoubleMetadata(mpi.planeDepths[d]));
            grids.push_back(g);
        }
    }
    return grids;
}

Mpi mpiFromGrids(const openvdb::GridPtrVec& grids, const PinholeCamera& camera,
                 const std::string& sourceName) {
    std::map<int, std::pair<openvdb::Vec3SGrid::Ptr, openvdb::FloatGrid::Ptr>> byPlane;
    for (const auto& g : grids) {
        const std::string name = g->getName();
        const bool isRgb = name.rfind(kMpiRgbGridStem, 0) == 0,
                   isAlpha = name.rfind(kMpiAlphaGridStem, 0) == 0;
        if (!isRgb && !isAlpha) continue;
        auto plane = g->getMetadata<openvdb::Int32Metadata>("mpi_plane");
        if (!plane)
            throw FileError(sourceName + ": grid '" + name + "' lacks 'mpi_plane' metadata");
        auto& entry = byPlane[plane->value()];
        if (isRgb) {
            entry.first = openvdb::gridPtrCast<openvdb::Vec3SGrid>(g);
            if (!entry.first)
                throw FileError(sourceName + ": grid '" + name + "' is " + gridKind(*g) +
                                ", expected a Vec3SGrid");
        } else {
            entry.second = openvdb::gridPtrCast<openvdb::FloatGrid>(g);
            if (!entry.second)
                throw FileError(sourceName + ": grid '" + name + "' is " + gridKind(*g) +
                                ", expected a FloatGrid");
        }
    }
    if (byPlane.empty())
        throw FileError(sourceName + ": holds no MPI planes (mpi_rgb_P*/mpi_alpha_P*)");
    Mpi mpi;
    mpi.camera = camera;
    const int w = camera.width, h = camera.height;
    int expected = 0;
    for (auto& [d, pair] : byPlane) {
        if (d != expected++)
            throw FileError(sourceName + ": MPI plane " + std::to_string(expected - 1) +
                            " is missing");
        if (!pair.first || !pair.second)
            throw FileError(sourceName + ": MPI plane " + std::to_string(d) +
                            " lacks its rgb or alpha grid");
        auto depth = pair.second->getMetadata<openvdb::DoubleMetadata>("mpi_depth");
        if (!depth)
            throw FileError(sourceName + ": MPI plane " + std::to_string(d) + " lacks 'mpi_depth'");
        mpi.planeDepths.push_back(depth->value());
        std::vector<float> plane(std::size_t(w) * h * 4, 0.f);
        auto rgbAcc = pair.first->getConstAccessor();
        auto alphaAcc = pair.second->getConstAccessor();
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const openvdb::Coord ijk(x, y, 0);
                const openvdb::Vec3s c = rgbAcc.getValue(ijk);
                float* p = &plane[(std::size_t(y) * w + x) * 4];
                p[0] = c.x();
                p[1] = c.y();
                p[2] = c.z();
                p[3] = alphaAcc.getValue(ijk);
            }
        mpi.planes.push_back(std::move(plane));
    }
    mpi.validate();
    return mpi;
}

}  // namespace lh
