// The height profile: its known values on a cube with two coloured slabs, which level-0 slice
// each voxel of a finer level reads, the "+profile" configurations, and a model without the
// profile carried over into one with it (same predictions until training uses the new inputs).
#include "net/height_profile.h"
#include "net/lighthouse_net.h"
#include "tests/net/net_test_scenes.h"

#include "core/errors.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh::net {
namespace {

TEST(HeightProfile, MeanColourAndCoverageOfEachSlice) {
    constexpr int64_t r = 16;
    auto cube = torch::zeros({1, 4, r, r, r});  // (rgb, alpha) over (z, y, x)
    // Slice y = 12: an opaque red floor over the whole slice.
    cube.select(3, 12).narrow(1, 0, 1).fill_(2.0);
    cube.select(3, 12).narrow(1, 3, 1).fill_(1.0);
    // Slice y = 3: green at alpha 0.5 over half the columns, and blue voxels with alpha 0
    // beside it, which must not tint the mean.
    cube.select(3, 3).narrow(3, 0, r / 2).narrow(1, 1, 1).fill_(0.5);
    cube.select(3, 3).narrow(3, 0, r / 2).narrow(1, 3, 1).fill_(0.5);
    cube.select(3, 3).narrow(3, r / 2, r / 2).narrow(1, 2, 1).fill_(7.0);
    const auto profile = heightProfile(cube);
    ASSERT_EQ(profile.sizes(), torch::IntArrayRef({1, 4, r}));
    const auto at = [&](int64_t c, int64_t y) { return profile[0][c][y].item<double>(); };
    EXPECT_NEAR(at(0, 12), 2.0, 1e-6);
    EXPECT_NEAR(at(1, 12), 0.0, 1e-6);
    EXPECT_NEAR(at(3, 12), 1.0 - std::exp(-double(r * r) / r), 1e-6);
    EXPECT_NEAR(at(0, 3), 0.0, 1e-6);
    EXPECT_NEAR(at(1, 3), 0.5, 1e-6);
    EXPECT_NEAR(at(2, 3), 0.0, 1e-6);
    // 128 voxels of alpha 0.5: sum 64, over R = 16.
    EXPECT_NEAR(at(3, 3), 1.0 - std::exp(-4.0), 1e-6);
    for (int64_t y : {0, 5, 15}) {
        EXPECT_EQ(at(3, y), 0.0) << "slice " << y;
        EXPECT_EQ(at(0, y), 0.0) << "slice " << y;
    }
}

TEST(HeightProfile, EachVoxelReadsTheLevelZeroSliceAtItsHeight) {
    constexpr int64_t slices = 16;
    const VolumeLayout layout{8.0, 3, int(slices)};
    // Slice j holds the value j in every channel.
    const auto profile =
        torch::arange(slices, torch::kFloat32).reshape({1, 1, slices}).expand({1, 4, slices});
    // Level 0 at its own resolution: voxel row i reads slice i.
    const auto level0 = heightProfileFeatures(profile, layout, 0, int(slices), /*hdr=*/false);
    ASSERT_EQ(level0.sizes(), torch::IntArrayRef({1, 4, slices, slices, slices}));
    // Level 1 spans the middle half of level 0's height: its row i (twice as fine) lies in slice
    // 4 + i / 2; the same for every z, x and channel.
    const auto level1 = heightProfileFeatures(profile, layout, 1, int(slices), false);
    for (int64_t i = 0; i < slices; ++i) {
        EXPECT_EQ(level0[0][1][3][i][5].item<float>(), float(i));
        EXPECT_EQ(level1[0][2][7][i][0].item<float>(), float(4 + i / 2)) << "row " << i;
        EXPECT_EQ(level1[0][3][0][i][15].item<float>(), float(4 + i / 2)) << "row " << i;
    }
    // HDR: colour as ln(1 + x), coverage as it is.
    const auto hdr = heightProfileFeatures(profile, layout, 0, int(slices), true);
    EXPECT_NEAR(hdr[0][0][0][9][0].item<float>(), std::log(10.0f), 1e-5);
    EXPECT_EQ(hdr[0][3][0][9][0].item<float>(), 9.0f);
}

TEST(HeightProfile, ProfileConfigurationsAreNamedBySuffix) {
    const NetConfig wide = NetConfig::byName("wide"), profiled = NetConfig::byName("wide+profile");
    EXPECT_FALSE(wide.heightProfile);
    EXPECT_TRUE(profiled.heightProfile);
    EXPECT_EQ(profiled.name, "wide+profile");
    EXPECT_EQ(profiled.baseWidth, wide.baseWidth);
    EXPECT_FALSE(profiled.sameParameters(wide));  // more input channels
    EXPECT_TRUE(NetConfig::fromJson(profiled.toJson(), "test").heightProfile);
    // Models written before the profile existed have no key, and load without one.
    EXPECT_FALSE(NetConfig::fromJson(wide.toJson(), "test").heightProfile);
    EXPECT_THROW(NetConfig::byName("+profile"), InputError);
    EXPECT_THROW(NetConfig::byName("wide+depth"), InputError);
}

TEST(HeightProfile, AModelWithoutItCarriesOverAndTheNewInputsThenReachTheCubes) {
    NetConfig plainConfig = test::tinyHdrConfig(), profiledConfig = plainConfig;
    profiledConfig.heightProfile = true;
    torch::manual_seed(12);
    LighthouseNet plain(plainConfig), profiled(profiledConfig);
    {
        torch::NoGradGuard noGrad;
        for (auto& p : plain->parameters()) p.add_(0.05 * torch::randn_like(p));
    }
    plain->eval();
    profiled->eval();
    const MatchedWeights m = copyMatchingWeights(profiled, plain);
    EXPECT_EQ(m.copied, m.tensors);  // every tensor: the stems with zero for the new inputs
    EXPECT_EQ(m.extended, plainConfig.levels);
    const PinholeCamera ref = test::planeCamera(64, 32),
                        src = test::planeCamera(64, 32, Vec3d(0.2, 0.0, 0.0));
    const PairInputs in =
        makePairInputs(test::renderPlane(ref, 2.0), test::renderPlane(src, 2.0), ref, src, 1.0, 4.0,
                       plainConfig, torch::Device(torch::kCPU));
    torch::NoGradGuard noGrad;
    const PipelineOutput a = plain->run(in), b = profiled->run(in);
    ASSERT_EQ(a.cubes.size(), b.cubes.size());
    for (size_t k = 0; k < a.cubes.size(); ++k)
        EXPECT_TRUE(torch::allclose(a.cubes[k], b.cubes[k], 1e-5, 1e-6)) << "level " << k;
    // Weight the profile's inputs of the coarsest network: its cube changes.
    auto stem = profiled->completion[0]->stem->weight;
    const int64_t inputs = stem.size(1);
    stem.narrow(1, inputs - kHeightProfileChannels, kHeightProfileChannels).fill_(0.1);
    const PipelineOutput c = profiled->run(in);
    EXPECT_GT((c.cubes[0] - a.cubes[0]).abs().max().item<double>(), 1e-3);
}

}  // namespace
}  // namespace lh::net
