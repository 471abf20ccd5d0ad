#include "render/first_medium.h"

#include "image/envmap_layout.h"
#include "render/envmap.h"
#include "render/free_space.h"
#include "tests/support/test_volumes.h"
#include "vdb/example_volume.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh {
namespace {

constexpr int W = 240, H = 120;

// Room-sized level (0.1 voxels over [-3, 3]^3) with one opaque block of side 0.8 at `centre`.
RenderVolume blockAt(const Vec3d& centre) {
    return RenderVolume(
        test::volumeOf({test::makeLevel(0.1, Vec3d(-3), openvdb::Coord(60),
                                        test::boxField(centre - Vec3d(0.4), centre + Vec3d(0.4),
                                                       {50.f, openvdb::Vec3s(1.f, 0.f, 0.f)}))}));
}

float startAt(const std::vector<float>& starts, int row, int column) {
    return starts[std::size_t(row) * W + column];
}

TEST(FirstMedium, ABlockIsMetWhereItsNearFaceIs) {
    // Block at +x, near face at x = 1.6. The field's support reaches one voxel further out than
    // the filled voxel centres (trilinear), so the start lies within a voxel and a half in front.
    const std::vector<float> starts = FirstMediumMap(blockAt(Vec3d(2, 0, 0)), Vec3d(0), W, H).all();
    const float right =
        startAt(starts, H / 2, 3 * W / 4);  // +x (docs/conventions.md#envmap-layout)
    EXPECT_LE(right, 1.6f);
    EXPECT_GE(right, 1.6f - 0.15f);
    // Looking away (-x), up (-y) or forward (+z) the ray never meets the block.
    EXPECT_TRUE(std::isinf(startAt(starts, H / 2, W / 4)));
    EXPECT_TRUE(std::isinf(startAt(starts, 0, 0)));
    EXPECT_TRUE(std::isinf(startAt(starts, H / 2, W / 2)));
}

TEST(FirstMedium, FootprintsWrapAroundTheSeamAndThePoles) {
    // Behind (-z) the block straddles the left/right seam: both edge columns meet it.
    const std::vector<float> behind =
        FirstMediumMap(blockAt(Vec3d(0, 0, -2)), Vec3d(0), W, H).all();
    EXPECT_LE(startAt(behind, H / 2, 0), 1.61f);
    EXPECT_LE(startAt(behind, H / 2, W - 1), 1.61f);
    // Straight up (-y, row 0) every column of the top row meets it.
    const std::vector<float> up = FirstMediumMap(blockAt(Vec3d(0, -2, 0)), Vec3d(0), W, H).all();
    for (int c = 0; c < W; ++c) ASSERT_LE(startAt(up, 0, c), 1.61f) << c;
    EXPECT_TRUE(std::isinf(startAt(up, H - 1, 0)));  // straight down sees nothing
}

TEST(FirstMedium, NoPixelsRayMeetsMediumBeforeItsStart) {
    // The promise the marcher relies on, checked by sampling the field along the rays.
    const RenderVolume room(makeExampleVolume(5, 32));
    for (const Vec3d& at : freeSpacePoints(room, 3, 7)) {
        const std::vector<float> starts = FirstMediumMap(room, at, W, H).all();
        int finite = 0;
        for (int r = 0; r < H; r += 5)
            for (int c = 0; c < W; c += 7) {
                const Vec3d d = envmapPixelDirection(r, c, W, H);
                const double start = startAt(starts, r, c);
                finite += std::isfinite(start);
                const double end = std::isfinite(start) ? start : 100.0;  // past the room
                for (int i = 0; i < 400; ++i) {
                    const double t = end * (i + 0.5) / 400;
                    ASSERT_EQ(room.sampleWorld(at + d * t).sigma, 0.f)
                        << "pixel " << r << "," << c << " at t " << t << " of start " << start;
                }
            }
        EXPECT_GT(finite, 0) << "a closed room is met in some direction";
    }
}

TEST(FirstMedium, EnvmapsAreTheSameWithAndWithoutIt) {
    const RenderVolume room(makeExampleVolume(5, 32));
    for (int nodes = 1; nodes <= 3; ++nodes) {
        EnvmapOptions skipping{W, H, MarchOptions{}};
        skipping.march.cellNodes = nodes;
        EnvmapOptions fromOrigin = skipping;
        fromOrigin.startAtFirstMedium = false;
        for (const Vec3d& at : freeSpacePoints(room, 2, 3)) {
            const ImageRGB a = renderEnvmap(room, at, skipping),
                           b = renderEnvmap(room, at, fromOrigin);
            double worst = 0.0;
            for (std::size_t i = 0; i < a.pixels.size(); ++i)
                worst = std::max(worst, std::abs(double(a.pixels[i]) - b.pixels[i]) /
                                            (1e-3 + std::abs(b.pixels[i])));
            EXPECT_LT(worst, 1e-5) << nodes << " nodes at " << at;  // rounding only
        }
    }
}

TEST(FirstMedium, MediumAFinerLevelHidesIsNeverMet) {
    // A coarse level's block at +x lies wholly inside a finer, empty level, which claims its
    // domain (finest wins): no ray meets it. Without the finer level, the +x ray does.
    const MediumSample opaque{50.f, openvdb::Vec3s(1.f, 0.f, 0.f)};
    const VolumeLevel coarse =
        test::makeLevel(0.1, Vec3d(-3), openvdb::Coord(60),
                        test::boxField(Vec3d(1.6, -0.4, -0.4), Vec3d(2.4, 0.4, 0.4), opaque));
    const VolumeLevel fine = test::makeLevel(0.05, Vec3d(1, -1, -1), openvdb::Coord(40),
                                             [](const Vec3d&) { return MediumSample{}; });
    const std::vector<float> hidden =
        FirstMediumMap(RenderVolume(test::volumeOf({coarse, fine})), Vec3d(0), W, H).all();
    for (float s : hidden) ASSERT_TRUE(std::isinf(s));
    const std::vector<float> seen =
        FirstMediumMap(RenderVolume(test::volumeOf({coarse})), Vec3d(0), W, H).all();
    EXPECT_LE(startAt(seen, H / 2, 3 * W / 4), 1.6f);
}

TEST(FirstMedium, AnOriginInsideTheMediumStartsEveryRayAtZero) {
    const std::vector<float> starts =
        FirstMediumMap(blockAt(Vec3d(0.2, 0, 0)), Vec3d(0), W, H).all();
    for (float s : starts) ASSERT_EQ(s, 0.f);
}

TEST(FirstMedium, BandsOfRowsAgreeWithTheWholeMap) {
    const RenderVolume room(makeExampleVolume(5, 32));
    const FirstMediumMap map(room, freeSpacePoints(room, 1, 11)[0], W, H);
    const std::vector<float> whole = map.all();
    std::vector<float> band(std::size_t(7) * W);
    for (int r0 = 0; r0 < H; r0 += 7) {
        const int r1 = std::min(H, r0 + 7);
        map.fillRows(r0, r1, band.data());
        for (int i = 0; i < (r1 - r0) * W; ++i)
            ASSERT_EQ(band[i], whole[std::size_t(r0) * W + i]) << r0 << " " << i;
    }
}

}  // namespace
}  // namespace lh
