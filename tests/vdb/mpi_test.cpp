#include "vdb/mpi.h"

#include "core/errors.h"
#include "vdb/example_volume.h"
#include "vdb/mantissa_rounding.h"
#include "vdb/volume_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

namespace lh {
namespace {

TEST(Mpi, PlanesAreLinearInDisparityBackToFront) {
    std::vector<double> depths = disparityLinearDepths(1.0, 8.0, 5);
    ASSERT_EQ(depths.size(), 5u);
    EXPECT_DOUBLE_EQ(depths.front(), 8.0);
    EXPECT_DOUBLE_EQ(depths.back(), 1.0);
    const double step = 1.0 / depths[1] - 1.0 / depths[0];
    for (int d = 1; d < 5; ++d) EXPECT_NEAR(1.0 / depths[d] - 1.0 / depths[d - 1], step, 1e-12);
    EXPECT_THROW(disparityLinearDepths(2.0, 1.0, 4), InputError);
    EXPECT_THROW(disparityLinearDepths(0.0, 1.0, 4), InputError);
}

TEST(Mpi, PlaneTransformPutsPixelsAtTheirWorldPosition) {
    PinholeCamera cam = exampleCameras().ref;
    // A turned and moved camera: the transform must carry the pose, not just the intrinsics.
    const double c = std::cos(0.3), s = std::sin(0.3);
    cam.rotation = Mat3d(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c);
    cam.position = Vec3d(0.5, -0.2, 1.0);
    const double depth = 3.7;
    auto xf = mpiPlaneTransform(cam, depth);
    EXPECT_TRUE(xf->isLinear());
    for (auto [u, v] : {std::pair{0, 0}, std::pair{17, 203}, std::pair{319, 239}}) {
        const Vec3d world = xf->indexToWorld(openvdb::Coord(u, v, 0));
        const Vec3d pixel = cam.cameraToPixel(cam.worldToCamera(world));
        EXPECT_NEAR(pixel.x(), u + 0.5, 1e-9);
        EXPECT_NEAR(pixel.y(), v + 0.5, 1e-9);
        EXPECT_NEAR(pixel.z(), depth, 1e-9);
    }
}

// OpenVDB's "nearly singular matrix" is turned into a message about the depth range.
TEST(Mpi, APlaneTooNearForOpenVdbIsBlamedOnTheNearDepth) {
    const PinholeCamera cam = exampleCameras().ref;
    try {
        mpiPlaneTransform(cam, 1e-12);
        FAIL() << "no error for a plane at 1e-12 m";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("the cameras' near depth is implausibly small"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_NO_THROW(mpiPlaneTransform(cam, 0.01));  // a centimetre is a plausible near depth
}

// An MPI of `planes` planes over a 40x30 crop of the example camera, depths 0.8-9.5, zeros.
Mpi smallMpi(int planes) {
    PinholeCamera cam = exampleCameras().ref;
    cam.width = 40;
    cam.height = 30;
    cam.cx = 20;
    cam.cy = 15;
    return Mpi::create(cam, 0.8, 9.5, planes);
}

TEST(Mpi, SaveLoadRoundTripIsExact) {
    Mpi mpi = smallMpi(6);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uni(0.f, 1.f);
    for (auto& plane : mpi.planes)
        for (float& x : plane) x = uni(rng) < 0.3f ? 0.f : uni(rng);  // zeros stay sparse
    const std::string path = (std::filesystem::temp_directory_path() / "lh_mpi.vdb").string();
    saveVdb(path, nullptr, &mpi);
    Mpi back = loadMpi(path);
    EXPECT_EQ(back.planeDepths, mpi.planeDepths);
    EXPECT_EQ(back.planes, mpi.planes);
    EXPECT_EQ(back.camera.fx, mpi.camera.fx);
    EXPECT_EQ(back.camera.width, 40);
}

// `predict --mantissa-bits` rounds the MPI as well as the volume: every colour and alpha reads
// back as its value rounded to N mantissa bits.
TEST(Mpi, MantissaRoundingReachesEveryPlane) {
    Mpi mpi = smallMpi(4);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(0.01f, 1.f);
    for (auto& plane : mpi.planes)
        for (float& x : plane) x = uni(rng);
    const std::string path = (std::filesystem::temp_directory_path() / "lh_mpi_m4.vdb").string();
    VolumeSaveOptions options;
    options.mantissaBits = 4;
    saveVdb(path, nullptr, &mpi, options);
    Mpi back = loadMpi(path);
    ASSERT_EQ(back.planes.size(), mpi.planes.size());
    int changed = 0;
    for (std::size_t d = 0; d < mpi.planes.size(); ++d)
        for (std::size_t i = 0; i < mpi.planes[d].size(); ++i) {
            const float x = mpi.planes[d][i], y = back.planes[d][i];
            ASSERT_EQ(y, roundToMantissaBits(x, 4)) << "plane " << d << " value " << i;
            changed += y != x;
        }
    EXPECT_GT(changed, 0);
}

}  // namespace
}  // namespace lh
