// The differentiable pipeline stage by stage: plane sweep, MPI rendering, resampling onto the
// cubes, and the training renderer against the C++ ray marcher.
#include "image/envmap_layout.h"
#include "image/image_io.h"
#include "net/lighthouse_net.h"
#include "net/losses.h"
#include "net/mpi_render.h"
#include "net/mpi_resample.h"
#include "net/psv.h"
#include "net/tensor_image.h"
#include "net/volume_export.h"
#include "net/volume_render.h"
#include "render/envmap.h"
#include "render/render_volume.h"
#include "tests/net/net_test_scenes.h"
#include "vdb/mpi.h"

#include <gtest/gtest.h>

namespace lh::net {
namespace {

using test::planeCamera;
using test::renderPlane;

TEST(PlaneSweep, TexturedPlaneIsSharpestAtTheNearestPlane) {
    const double planeDepth = 2.3;
    const PinholeCamera ref = planeCamera(64, 48), src = planeCamera(64, 48, Vec3d(0.25, 0.0, 0.0));
    const auto refImage = imageToTensor(renderPlane(ref, planeDepth));
    const auto srcImage = imageToTensor(renderPlane(src, planeDepth));
    const std::vector<double> depths = disparityLinearDepths(1.0, 6.0, 16);
    const auto psv = planeSweepVolume(refImage, srcImage, ref, src, depths);
    ASSERT_EQ(psv.sizes(), (std::vector<int64_t>{1, 6, 16, 48, 64}));

    // Compare over the columns every plane's warp keeps inside the source image.
    const auto diff =
        (psv.narrow(1, 0, 3) - psv.narrow(1, 3, 3)).abs().narrow(4, 0, 24).mean({0, 1, 3, 4});
    const int64_t best = diff.argmin().item<int64_t>();
    int64_t nearest = 0;
    for (size_t d = 0; d < depths.size(); ++d)
        if (std::abs(1 / depths[d] - 1 / planeDepth) <
            std::abs(1 / depths[size_t(nearest)] - 1 / planeDepth))
            nearest = int64_t(d);
    EXPECT_EQ(best, nearest);
    EXPECT_LT(diff[best].item<double>(), 0.75 * diff.median().item<double>());
}

TEST(MpiRender, OpaquePlaneReprojectsIntoTheTargetView) {
    // One opaque plane carrying the texture at depth 2: the target view must see the texture
    // where the analytic rendering does.
    const PinholeCamera ref = planeCamera(96, 64),
                        tgt = planeCamera(96, 64, Vec3d(0.1, -0.05, 0.2));
    const std::vector<double> depths = disparityLinearDepths(1.5, 3.0, 16);
    auto mpi = torch::zeros({1, 4, 16, 64, 96});
    const int plane = 7;
    const auto texture = imageToTensor(renderPlane(ref, depths[plane]));
    mpi.index_put_({0, torch::indexing::Slice(0, 3), plane}, texture.squeeze(0));
    mpi.index_put_({0, 3, plane}, 1.0);
    const ImageRGB rendered = tensorToImage(renderMpiView(mpi, depths, ref, tgt));
    const ImageRGB expected = renderPlane(tgt, depths[plane]);
    double err = 0;
    int n = 0;
    for (int v = 8; v < 56; ++v)
        for (int u = 12; u < 84; ++u)
            for (int c = 0; c < 3; ++c, ++n)
                err += std::abs(rendered.at(u, v)[c] - expected.at(u, v)[c]);
    EXPECT_LT(err / n, 0.02);
}

TEST(MpiResample, PlaneContentLandsAtItsWorldPosition) {
    const PinholeCamera ref = planeCamera(64, 48);
    const std::vector<double> depths = disparityLinearDepths(1.0, 4.0, 16);
    const int plane = 6;
    auto mpi = torch::zeros({1, 4, 16, 48, 64});
    mpi.index_put_({0, 0, plane}, 1.0);  // red
    mpi.index_put_({0, 3, plane}, 0.8);
    const VolumeLayout layout = VolumeLayout::fromFarDepth(4.0, 2, 32);
    for (int level = 0; level < 2; ++level) {
        const auto cube = resampleMpiToLevel(mpi, depths, ref, layout, level);
        ASSERT_EQ(cube.sizes(), (std::vector<int64_t>{1, 4, 32, 32, 32}));
        const auto centres = voxelCentres(layout, level);
        const auto alpha = cube[0][3];
        int occupied = 0;
        const double spacing =
            depths[plane] * depths[plane] * (1 / depths.back() - 1 / depths.front()) / 15;
        for (int z = 0; z < 32; ++z)
            for (int y = 0; y < 32; ++y)
                for (int x = 0; x < 32; ++x) {
                    const float a = alpha[z][y][x].item<float>();
                    if (a <= 1e-4f) continue;
                    ++occupied;
                    const double wz = centres[z][y][x][2].item<double>();
                    // Only voxels within one plane spacing of the plane's depth, inside the
                    // frustum.
                    EXPECT_LT(std::abs(wz - depths[plane]), spacing + 1e-9) << "level " << level;
                    const Vec3d px =
                        ref.cameraToPixel(Vec3d(centres[z][y][x][0].item<double>(),
                                                centres[z][y][x][1].item<double>(), wz));
                    EXPECT_TRUE(px.x() >= 0 && px.x() <= 64 && px.y() >= 0 && px.y() <= 48);
                    EXPECT_NEAR(cube[0][0][z][y][x].item<float>(), 1.f,
                                1e-4);  // premultiplied: still red
                    EXPECT_NEAR(cube[0][1][z][y][x].item<float>(), 0.f, 1e-4);
                }
        EXPECT_GT(occupied, 0) << "level " << level;
    }
}

TEST(MpiResample, VoxelOpacityFollowsTheDensityConvention) {
    // A uniform MPI of plane alpha a has density -ln(1 - a) / spacing: a voxel of side v
    // deep inside it has opacity 1 - (1 - a)^(v / spacing).
    const PinholeCamera ref = planeCamera(64, 48);
    const std::vector<double> depths = disparityLinearDepths(2.0, 4.0, 16);
    auto mpi = torch::zeros({1, 4, 16, 48, 64});
    mpi.narrow(1, 3, 1).fill_(0.3);
    mpi.narrow(1, 1, 1).fill_(0.5);
    const VolumeLayout layout = VolumeLayout::fromFarDepth(4.0, 1, 32);
    const auto cube = resampleMpiToLevel(mpi, depths, ref, layout, 0);
    const auto centres = voxelCentres(layout, 0);
    // Voxel on the optical axis at depth ~3.
    const int x = 16, y = 16, z = int((3.0 - layout.box(0).min.z()) / layout.voxelSize(0));
    const double depth = centres[z][y][x][2].item<double>();
    const double spacing = depth * depth * (1 / 2.0 - 1 / 4.0) / 15;
    const double expected = 1 - std::pow(0.7, layout.voxelSize(0) / spacing);
    EXPECT_NEAR(cube[0][3][z][y][x].item<double>(), expected, 1e-4);
    EXPECT_NEAR(cube[0][1][z][y][x].item<double>(), 0.5, 1e-5);
}

// A two-level test volume: an emissive orange block in level 0, a blue-ish foggy slab in
// level 1 and a red block behind the query point.
std::vector<torch::Tensor> testCubes(const VolumeLayout& layout) {
    std::vector<torch::Tensor> cubes;
    for (int k = 0; k < layout.levels; ++k) {
        const auto centres = voxelCentres(layout, k).to(torch::kFloat32);
        const auto x = centres.select(-1, 0), y = centres.select(-1, 1), z = centres.select(-1, 2);
        auto cube = torch::zeros({1, 4, layout.resolution, layout.resolution, layout.resolution});
        const auto block = (x > 0.8) & (x < 1.6) & (y.abs() < 0.6) & (z.abs() < 0.5);
        const auto slab = (z > 0.9) & (z < 1.3) & (x.abs() < 0.6);
        const auto back = (z < -1.0) & (z > -1.8) & (x.abs() < 0.8);
        cube[0][0].masked_fill_(block, 1.0).masked_fill_(slab, 0.2).masked_fill_(back, 0.9);
        cube[0][1].masked_fill_(block, 0.5).masked_fill_(slab, 0.4).masked_fill_(back, 0.1);
        cube[0][2].masked_fill_(slab, 0.9).masked_fill_(back, 0.1);
        cube[0][3].masked_fill_(block, 0.9).masked_fill_(slab, 0.2).masked_fill_(back, 0.95);
        cubes.push_back(cube);
    }
    return cubes;
}

TEST(TrainingRenderer, AgreesWithTheRayMarcher) {
    const VolumeLayout layout = VolumeLayout::fromFarDepth(2.0, 2, 32);  // s0 = 4
    const auto cubes = testCubes(layout);
    const RenderVolume volume(cubesToVolume(cubes, layout));
    for (const Vec3d& p : {Vec3d(0.0, 0.0, 0.3), Vec3d(0.3, -0.2, 0.6)}) {
        const ImageRGB torchEnv = tensorToImage(renderEnvmapTorch(cubes, layout, p, 64, 32, 256));
        EnvmapOptions options;
        options.width = 64;
        options.height = 32;
        options.march.stepVoxels = 0.25;
        options.march.minTransmittance = 0;
        const ImageRGB marched = renderEnvmap(volume, p, options);
        double se = 0, mean = 0;
        for (size_t i = 0; i < marched.pixels.size(); ++i) {
            se += std::pow(torchEnv.pixels[i] - marched.pixels[i], 2);
            mean += marched.pixels[i];
        }
        const double rmse = std::sqrt(se / marched.pixels.size()),
                     meanRadiance = mean / marched.pixels.size();
        ASSERT_GT(meanRadiance, 0.02);
        // Stated tolerance: 3% of the mean radiance (the two differ only in sample placement
        // and in how a finer level's edge voxels interpolate: a clamped border here, the
        // coarser level's values there).
        EXPECT_LT(rmse, 0.03 * meanRadiance) << "at " << p;
        // The orange block at +x is seen at column 3W/4 in both.
        EXPECT_GT(torchEnv.at(48, 16)[0], 0.5f);
        EXPECT_GT(marched.at(48, 16)[0], 0.5f);
    }
}

TEST(TrainingRenderer, HomogeneousMediumMatchesTheAnalyticAnswer) {
    // A single level filled with colour c at opacity a per voxel, seen from its centre:
    // radiance along every ray = c (1 - exp(-sigma * distance to the face)), and the ray
    // leaves through the face with exp(-sigma * distance) of its transmittance, whose mean
    // is the closed-room prior.
    const VolumeLayout layout = VolumeLayout::fromFarDepth(1.0, 1, 16);  // cube of side 2
    auto cube = torch::zeros({1, 4, 16, 16, 16});
    cube.narrow(1, 0, 3).fill_(0.7);
    cube.narrow(1, 3, 1).fill_(0.05);
    const double sigma = -std::log(0.95) / layout.voxelSize(0);
    const TorchEnvmap env =
        renderEnvmapAndTransmittanceTorch({cube}, layout, Vec3d(0.0), 16, 8, 512);
    ASSERT_EQ(env.transmittance.sizes(), (std::vector<int64_t>{1, 1, 8, 16}));
    EXPECT_TRUE(
        torch::allclose(env.radiance, renderEnvmapTorch({cube}, layout, Vec3d(0.0), 16, 8, 512)));
    const ImageRGB image = tensorToImage(env.radiance);
    double meanLeft = 0;
    for (int row = 0; row < 8; ++row)
        for (int col = 0; col < 16; ++col) {
            const Vec3d d = envmapPixelDirection(row, col, 16, 8);
            const double toFace =
                1.0 / std::max({std::abs(d.x()), std::abs(d.y()), std::abs(d.z())});
            // The outermost half voxel fades to empty (nothing outside level 0): stated 4%.
            const double expected = 0.7 * (1 - std::exp(-sigma * toFace));
            EXPECT_NEAR(image.at(col, row)[1], expected, 0.04 * expected) << row << "," << col;
            const double left = env.transmittance[0][0][row][col].item<double>();
            EXPECT_NEAR(-std::log(left), sigma * toFace, 0.04 * sigma * toFace)
                << row << "," << col;
            meanLeft += left / (8 * 16);
        }
    EXPECT_NEAR(closureLoss(env.transmittance).item<double>(), meanLeft, 1e-5);
}

TEST(TrainingRenderer, ClosedRoomPriorIsZeroInsideAnOpaqueMediumAndOneWithoutMedium) {
    const VolumeLayout layout = VolumeLayout::fromFarDepth(1.0, 1, 16);
    auto cube = torch::zeros({1, 4, 16, 16, 16});
    const auto empty = renderEnvmapAndTransmittanceTorch({cube}, layout, Vec3d(0.0), 16, 8, 64);
    EXPECT_NEAR(closureLoss(empty.transmittance).item<double>(), 1.0, 1e-7);
    cube.narrow(1, 3, 1).fill_(0.9);
    const auto opaque = renderEnvmapAndTransmittanceTorch({cube}, layout, Vec3d(0.0), 16, 8, 64);
    EXPECT_LT(closureLoss(opaque.transmittance).item<double>(), 1e-6);
}

TEST(TrainingRenderer, PruningInTrainingRendersWhatPredictExportsWithStraightThroughGradients) {
    // The test volume in a faint fog (alpha 0.05) pruned at 0.1: the forward pass holds the
    // alphas predict would export, so the training render agrees with the ray marcher over
    // the exported volume and loses the fog's light; the backward pass is the identity, so a
    // loss can still raise a pruned voxel above the threshold.
    const VolumeLayout layout = VolumeLayout::fromFarDepth(2.0, 2, 32);
    std::vector<torch::Tensor> cubes = testCubes(layout);
    for (auto& cube : cubes) {
        const auto empty = cube.narrow(1, 3, 1) == 0;
        cube.narrow(1, 3, 1).masked_fill_(empty, 0.05);
        cube.narrow(1, 0, 3).masked_fill_(empty.expand({1, 3, -1, -1, -1}), 0.6);
        cube.requires_grad_(true);
    }
    const double threshold = 0.1;
    const auto pruned = pruneCubesStraightThrough(cubes, threshold);
    ASSERT_EQ(pruned.size(), cubes.size());
    for (size_t k = 0; k < cubes.size(); ++k) {
        const auto alpha = cubes[k].narrow(1, 3, 1).detach();
        const auto expected = torch::where(alpha >= threshold, alpha, torch::zeros_like(alpha));
        EXPECT_TRUE(torch::equal(pruned[k].narrow(1, 3, 1).detach(), expected)) << "level " << k;
        EXPECT_TRUE(
            torch::equal(pruned[k].narrow(1, 0, 3).detach(), cubes[k].narrow(1, 0, 3).detach()));
    }

    const Vec3d p(0.0, 0.0, 0.3);
    const auto torchEnv = renderEnvmapTorch(pruned, layout, p, 64, 32, 256);
    EnvmapOptions options;
    options.width = 64;
    options.height = 32;
    options.march.stepVoxels = 0.25;
    options.march.minTransmittance = 0;
    const ImageRGB exported =
        renderEnvmap(RenderVolume(cubesToVolume(cubes, layout, float(threshold))), p, options);
    const ImageRGB foggy = tensorToImage(renderEnvmapTorch(cubes, layout, p, 64, 32, 256));
    const ImageRGB prunedImage = tensorToImage(torchEnv);
    double se = 0, seFog = 0, mean = 0;
    for (size_t i = 0; i < exported.pixels.size(); ++i) {
        se += std::pow(prunedImage.pixels[i] - exported.pixels[i], 2);
        seFog += std::pow(foggy.pixels[i] - exported.pixels[i], 2);
        mean += exported.pixels[i];
    }
    const double n = double(exported.pixels.size());
    // As AgreesWithTheRayMarcher: 3% of the mean radiance; the fog is far more than that.
    EXPECT_LT(std::sqrt(se / n), 0.03 * mean / n);
    EXPECT_GT(std::sqrt(seFog / n), 0.1 * mean / n);

    torchEnv.sum().backward();
    for (size_t k = 0; k < cubes.size(); ++k) {
        const auto grad = cubes[k].grad().narrow(1, 3, 1);
        const auto fog = cubes[k].narrow(1, 3, 1).detach() < threshold;
        // Pruned voxels in view of the point still receive the gradient of their light.
        EXPECT_GT(grad.masked_select(fog).abs().max().item<double>(), 0.0) << "level " << k;
    }
    EXPECT_EQ(pruneCubesStraightThrough(cubes, 0.0)[0].data_ptr(), cubes[0].data_ptr());
}

}  // namespace
}  // namespace lh::net
