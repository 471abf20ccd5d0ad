#include "render/radial_shell.h"

#include "core/errors.h"
#include "image/envmap_layout.h"
#include "render/envmap.h"
#include "tests/support/test_volumes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace lh {
namespace {

// Two nested levels of 32^3: level 0 is 8 units wide around the origin, level 1 4 units wide
// in front of it (z in [0, 4]). The default centre is (0, 0, 1).
VolumeLayout smallLayout() { return VolumeLayout{8.0, 2, 32}; }

LightingVolume onSmallLayout(const std::function<MediumSample(const Vec3d&)>& field) {
    LightingVolume volume = LightingVolume::fromLayout(smallLayout());
    for (int k = 0; k < 2; ++k) volume.fillLevel(k, field);
    return volume;
}

// Translucent fog between 1.5 and 3 units from `centre`, red towards +x, blue elsewhere: along
// each ray from the centre it is spread over 1.5 units (12 voxels of level 1) and lets 47% of
// the light through.
MediumSample fogAround(const Vec3d& centre, const Vec3d& p) {
    const Vec3d d = p - centre;
    const double r = d.length();
    if (r < 1.5 || r > 3.0) return {};
    return {0.5f, d.x() > 0.0 ? openvdb::Vec3s(1.f, 0.f, 0.f) : openvdb::Vec3s(0.f, 0.f, 1.f)};
}

double relativeRmse(const ImageRGB& a, const ImageRGB& b) {
    double squared = 0, sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        squared += (a.pixels[i] - b.pixels[i]) * double(a.pixels[i] - b.pixels[i]);
        sum += b.pixels[i];
    }
    const double n = double(a.pixels.size());
    return std::sqrt(squared / n) / (sum / n);
}

TEST(RadialShell, KeepsTheEnvmapSeenFromItsCentreWithFarFewerVoxels) {
    const Vec3d centre = defaultShellCentre(smallLayout());
    ASSERT_EQ(centre, Vec3d(0, 0, 1));
    const LightingVolume fog = onSmallLayout([&](const Vec3d& p) { return fogAround(centre, p); });
    const LightingVolume shell = collapseToShell(fog, centre);

    const EnvmapOptions options{120, 60, MarchOptions{}};
    const ImageRGB before = renderEnvmap(RenderVolume(fog), centre, options);
    const ImageRGB after = renderEnvmap(RenderVolume(shell), centre, options);
    // The same light from the centre, up to the lattice and the cube map of directions.
    EXPECT_LT(relativeRmse(after, before), 0.05);
    // Red at +x (column 3W/4), blue at -x (column W/4), as before.
    EXPECT_GT(after.at(90, 30)[0], 0.4f);
    EXPECT_LT(after.at(90, 30)[2], 0.05f);
    EXPECT_GT(after.at(30, 30)[2], 0.4f);
    // A layer three voxels thick instead of fog twelve voxels thick.
    EXPECT_LT(shell.activeVoxelCount(), fog.activeVoxelCount() / 2);
    // And opaque: a ray from the centre stops in it, with the composite colour
    // 1 - exp(-0.5 x 1.5) = 0.53 of red.
    const RayResult ray = marchRay(RenderVolume(shell), centre, Vec3d(1, 0, 0), MarchOptions{});
    EXPECT_LT(ray.transmittance, 0.01);
    EXPECT_NEAR(ray.radiance[0], 1.0 - std::exp(-0.75), 0.03);
    // The layer is centred where the fog had gathered half its alpha, 1 - exp(-0.5 (t - 1.5))
    // = 0.53 / 2 at t = 2.11, and is 1.5 voxels of level 0 (0.375) deep on either side: the
    // ray stops in its front half.
    const double median = 1.5 - 2.0 * std::log(1.0 - 0.5 * (1.0 - std::exp(-0.75)));
    EXPECT_NEAR(median, 2.11, 0.01);
    EXPECT_GT(ray.surfaceDistance, median - 0.375);
    EXPECT_LT(ray.surfaceDistance, median);
}

TEST(RadialShell, FillsTheEdgeOfANearObjectSoThatNoRayEscapesBehindIt) {
    // A closed wall 2.5 units from the centre and an opaque block in front of it. Seen from the
    // centre, the block hides a patch of the wall; the shell holds the block's face there.
    const Vec3d centre = defaultShellCentre(smallLayout());
    const LightingVolume room = onSmallLayout([&](const Vec3d& p) -> MediumSample {
        const Vec3d d = p - centre;
        if (std::abs(d.length() - 2.5) < 0.15) return {20.f, openvdb::Vec3s(0.5f)};
        if (std::abs(d.x()) < 0.3 && std::abs(d.y()) < 0.3 && d.z() > 0.8 && d.z() < 1.2)
            return {20.f, openvdb::Vec3s(1.f, 1.f, 0.f)};
        return {};
    });
    const RenderVolume shell(collapseToShell(room, centre));
    // From a point beside the centre, a ray that passes the block's edge and ends on the wall
    // behind the block: the wall there is hidden from the centre, so without the skirt joining
    // the block's edge to the wall this ray would leave the volume.
    const Vec3d from = centre + Vec3d(0.9, 0, 0), to = centre + Vec3d(0, 0, 2.5);
    const RayResult ray = marchRay(shell, from, (to - from).unit(), MarchOptions{});
    EXPECT_LT(ray.transmittance, 0.01);
    // In the original room the same ray misses the block too and stops on the wall.
    const RayResult original =
        marchRay(RenderVolume(room), from, (to - from).unit(), MarchOptions{});
    EXPECT_LT(original.transmittance, 0.01);
    EXPECT_NEAR(original.radiance[2], 0.5, 0.05);  // the grey wall, not the yellow block
}

TEST(RadialShell, EmptyVolumeStaysEmpty) {
    const LightingVolume empty = LightingVolume::fromLayout(smallLayout());
    EXPECT_EQ(collapseToShell(empty, Vec3d(0, 0, 1)).activeVoxelCount(), 0u);
}

TEST(RadialShell, RefusesWhatItCannotCollapse) {
    const LightingVolume fog =
        onSmallLayout([](const Vec3d& p) { return fogAround(Vec3d(0, 0, 1), p); });
    // Outside level 0 (which spans [-4, 4]^3), or not a point.
    EXPECT_THROW(collapseToShell(fog, Vec3d(5, 0, 0)), InputError);
    EXPECT_THROW(collapseToShell(fog, Vec3d(0, std::nan(""), 0)), InputError);
    RadialShellOptions thin;
    thin.halfWidthVoxels = 0.1;
    EXPECT_THROW(collapseToShell(fog, Vec3d(0, 0, 1), thin), InputError);
    RadialShellOptions coarse;
    coarse.directionsPerFace = 2;
    EXPECT_THROW(collapseToShell(fog, Vec3d(0, 0, 1), coarse), InputError);
    // A volume without the nested layout (a foreign file's levels).
    const LightingVolume foreign =
        test::volumeOf({test::makeLevel(0.1, Vec3d(-1), openvdb::Coord(20), [](const Vec3d&) {
            return MediumSample{1.f, {}};
        })});
    EXPECT_THROW(collapseToShell(foreign, Vec3d(0)), InputError);
}

// A camera at the origin looking along +z, 64x48 pixels with a 77 degree wide view: it sees
// the fog in front of the default centre (0, 0, 1) and none of the fog behind it.
PinholeCamera forwardCamera() {
    PinholeCamera camera;
    camera.width = 64;
    camera.height = 48;
    camera.fx = camera.fy = 40.0;
    camera.cx = 32.0;
    camera.cy = 24.0;
    return camera;
}

TEST(RadialShell, KeepsTheMediumTheCameraSeesAsItIs) {
    const Vec3d centre = defaultShellCentre(smallLayout());
    LightingVolume fog = onSmallLayout([&](const Vec3d& p) { return fogAround(centre, p); });
    fog.refCamera = forwardCamera();
    const LightingVolume shell = collapseToShell(fog, centre);
    RadialShellOptions collapseAll;
    collapseAll.keepCameraView = false;
    const LightingVolume collapsed = collapseToShell(fog, centre, collapseAll);
    EXPECT_TRUE(keepsCameraView(fog, {}));
    EXPECT_FALSE(keepsCameraView(fog, collapseAll));

    // Fog the camera sees (ahead, in its blue half, 2.06 units from the centre) is kept as it
    // was: density 0.5 per unit, blue. Collapsed, the same place holds an opaque layer.
    const Vec3d seen(-0.5, 0.0, 3.0);
    const RenderSample keptSample = RenderVolume(shell).sampleWorld(seen);
    EXPECT_NEAR(keptSample.sigma, 0.5f, 1e-6);
    EXPECT_NEAR(keptSample.emission[2], 0.5f, 1e-6);  // sigma x blue 1
    EXPECT_GT(std::abs(RenderVolume(collapsed).sampleWorld(seen).sigma - 0.5f), 0.1f);
    // Fog behind the camera, which it does not see, is collapsed all the same.
    const Vec3d unseen(0.0, 0.0, -1.0);
    EXPECT_GT(std::abs(RenderVolume(shell).sampleWorld(unseen).sigma - 0.5f), 0.1f);
    EXPECT_LT(shell.activeVoxelCount(), fog.activeVoxelCount());
    EXPECT_GT(shell.activeVoxelCount(), collapsed.activeVoxelCount());

    // Seen from the centre the shell gives the fog's envmap.
    const EnvmapOptions options{120, 60, MarchOptions{}};
    EXPECT_LT(relativeRmse(renderEnvmap(RenderVolume(shell), centre, options),
                           renderEnvmap(RenderVolume(fog), centre, options)),
              0.05);
    // From another point, a ray that crosses the fog in the camera's view at a slant, from its
    // red half (x > 0) into its blue half, gathers both as before; the collapsed layer gives it
    // the one colour the centre saw where the ray meets it.
    const Vec3d aside = centre + Vec3d(0.6, 0.3, 0.3);
    const Vec3d slant = Vec3d(-0.25, 0.0, 1.0).unit();
    const RayResult before = marchRay(RenderVolume(fog), aside, slant, MarchOptions{});
    const RayResult kept = marchRay(RenderVolume(shell), aside, slant, MarchOptions{});
    const RayResult flat = marchRay(RenderVolume(collapsed), aside, slant, MarchOptions{});
    ASSERT_GT(before.radiance[0], 0.05);
    ASSERT_GT(before.radiance[2], 0.05);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(kept.radiance[c], before.radiance[c], 1e-3) << c;
    EXPECT_GT(std::abs(flat.radiance[0] - before.radiance[0]) +
                  std::abs(flat.radiance[2] - before.radiance[2]),
              0.1);
}

TEST(RadialShell, WithoutACameraCollapsesEverything) {
    const Vec3d centre = defaultShellCentre(smallLayout());
    const LightingVolume fog = onSmallLayout([&](const Vec3d& p) { return fogAround(centre, p); });
    ASSERT_FALSE(fog.refCamera);
    EXPECT_FALSE(keepsCameraView(fog, {}));
    const LightingVolume shell = collapseToShell(fog, centre);
    EXPECT_GT(std::abs(RenderVolume(shell).sampleWorld(Vec3d(0.0, 0.0, 3.0)).sigma - 0.5f), 0.1f);
}

TEST(RadialShell, TheShellRecordsItsCentre) {
    const Vec3d centre = defaultShellCentre(smallLayout()) + Vec3d(0.1, -0.2, 0.0);
    const LightingVolume fog = onSmallLayout([&](const Vec3d& p) { return fogAround(centre, p); });
    ASSERT_FALSE(fog.shellCentre);
    const LightingVolume shell = collapseToShell(fog, centre);
    ASSERT_TRUE(shell.shellCentre);
    EXPECT_EQ(*shell.shellCentre, centre);
}

TEST(RadialShell, OneVoxelOfTheLayerLetsATenThousandthOfTheLightThrough) {
    const Vec3d centre = defaultShellCentre(smallLayout());
    const LightingVolume fog = onSmallLayout([&](const Vec3d& p) { return fogAround(centre, p); });
    const LightingVolume shell = collapseToShell(fog, centre);  // no camera: all collapsed
    for (int k = 0; k < 2; ++k) {
        const double voxel = smallLayout().voxelSize(k);
        EXPECT_NEAR(std::exp(-shellLayerDensity(voxel) * voxel), 1e-4, 1e-7) << k;
        std::size_t layerVoxels = 0;
        for (auto it = shell.levels[k].density->cbeginValueOn(); it; ++it, ++layerVoxels)
            ASSERT_FLOAT_EQ(*it, shellLayerDensity(voxel)) << k;
        EXPECT_GT(layerVoxels, 0u) << k;
    }
}

TEST(RadialShell, AShellThatDoesNotRecordItsCentreIsRecognised) {
    const Vec3d centre = defaultShellCentre(smallLayout());
    LightingVolume fog = onSmallLayout([&](const Vec3d& p) { return fogAround(centre, p); });
    fog.refCamera = forwardCamera();
    LightingVolume shell = collapseToShell(fog, centre);
    EXPECT_FALSE(looksLikeUnmarkedShell(fog));
    shell.shellCentre.reset();  // as written before shells recorded it
    EXPECT_TRUE(looksLikeUnmarkedShell(shell));
    // Without the camera the kept fog counts too, and it is no layer.
    LightingVolume withoutCamera = shell;  // shares the grids, which it does not change
    withoutCamera.refCamera.reset();
    EXPECT_FALSE(looksLikeUnmarkedShell(withoutCamera));

    // Every density outside the camera's view scaled: 0.5% (what rounding to 7 mantissa bits
    // may do) is still the layer, 3% (an edit) is not.
    const auto scaled = [&](float factor) {
        LightingVolume v = shell;  // its grids are shared: copy them before scaling
        for (VolumeLevel& level : v.levels) {
            level.density = level.density->deepCopy();
            for (auto it = level.density->beginValueOn(); it; ++it)
                if (!v.refCamera->projectIntoImage(level.transform().indexToWorld(it.getCoord())))
                    it.setValue(*it * factor);
        }
        return v;
    };
    EXPECT_TRUE(looksLikeUnmarkedShell(scaled(1.005f)));
    EXPECT_FALSE(looksLikeUnmarkedShell(scaled(1.03f)));
    // Shells written before had a layer of half the density (1% through a voxel, not 1e-4).
    EXPECT_TRUE(looksLikeUnmarkedShell(scaled(float(std::log(0.01) / std::log(1e-4)))));
    EXPECT_FALSE(looksLikeUnmarkedShell(scaled(0.75f)));

    // Nothing outside the camera's view, nothing to recognise.
    EXPECT_FALSE(looksLikeUnmarkedShell(LightingVolume::fromLayout(smallLayout())));
}

}  // namespace
}  // namespace lh
