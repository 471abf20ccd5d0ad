// Whole examples: determinism, stereo geometry and files (oracle_test.cpp: the oracle's ceiling).
#include "synth/dataset.h"

#include "image/image_io.h"
#include "synth/oracle.h"
#include "synth/scene_json.h"
#include "tests/synth/synth_test_options.h"
#include "tests/synth/synth_test_scenes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace lh::synth {
namespace {

namespace fs = std::filesystem;

using test::freshDir;
using test::smallOptions;

std::string bytesOf(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(SynthDataset, SameSeedGivesIdenticalFiles) {
    const fs::path dir = freshDir("determinism");
    const SynthOptions o = smallOptions(dir.string());
    PanoramaLibrary panoramas(o.hdriDir);
    writeExample(exampleSeed("train", 7), (dir / "a").string(), o, panoramas);
    writeExample(exampleSeed("train", 7), (dir / "b").string(), o, panoramas);
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir / "a")) {
        const fs::path other = dir / "b" / entry.path().filename();
        ASSERT_TRUE(fs::exists(other)) << other;
        EXPECT_EQ(bytesOf(entry.path()), bytesOf(other)) << entry.path().filename();
        ++files;
    }
    EXPECT_EQ(files, 13);  // 3 views x (exr, png) + depth + env (exr, png, mask, pos) + 2 json
    EXPECT_NE(exampleSeed("train", 3), exampleSeed("test", 3));
}

TEST(SynthDataset, ManifestRecordsTheRoomLampLayoutOnlyWhenChosen) {
    const auto manifestOf = [](const std::string& name, LampLayout layout) {
        const fs::path dir = freshDir(name);
        SynthOptions o = smallOptions(dir.string());
        o.count = 1;
        o.lampLayout = layout;
        writeDataset(o);
        return nlohmann::json::parse(bytesOf(dir / "manifest.json"));
    };
    EXPECT_EQ(manifestOf("layout_room", LampLayout::Room).value("lamp_layout", ""), "room");
    // Sets made with the default keep the header they had before the option.
    EXPECT_FALSE(manifestOf("layout_random", LampLayout::Random).contains("lamp_layout"));
}

TEST(SynthDataset, StereoPairSatisfiesEpipolarGeometry) {
    const fs::path dir = freshDir("stereo");
    const SynthOptions o = smallOptions(dir.string());
    PanoramaLibrary panoramas(o.hdriDir);
    writeExample(exampleSeed("train", 11), (dir / "x").string(), o, panoramas);
    const CamerasFile cams = loadCamerasFile((dir / "x" / "cameras.json").string());
    ASSERT_TRUE(cams.src && cams.near && cams.far);
    EXPECT_LT(*cams.near, *cams.far);
    EXPECT_EQ(cams.src->rotation, cams.ref.rotation);
    const double baseline = cams.src->position.x();
    EXPECT_GE(baseline, 0.05);
    EXPECT_LE(baseline, 0.15);
    EXPECT_EQ(cams.src->position.y(), 0.0);

    const ImageRGB depth = readImage((dir / "x" / "depth.exr").string());
    const ImageRGB ref = readImage((dir / "x" / "ref.exr").string());
    const ImageRGB src = readImage((dir / "x" / "src.exr").string());
    int agree = 0, checked = 0;
    for (int y = 4; y < ref.height - 4; y += 7)
        for (int x = 4; x < ref.width - 4; x += 7) {
            // The 3D point seen at (x, y) in ref projects into src on the same row, shifted
            // by the disparity fx * baseline / depth.
            const double z = depth.at(x, y)[0];
            const Vec3d world = cams.ref.pixelDirection(x + 0.5, y + 0.5) *
                                (z / cams.ref.pixelDirection(x + 0.5, y + 0.5).z());
            const Vec3d inSrc = cams.src->cameraToPixel(cams.src->worldToCamera(world));
            ASSERT_NEAR(inSrc.y(), y + 0.5, 1e-6);
            ASSERT_NEAR((x + 0.5) - inSrc.x(), cams.ref.fx * baseline / z, 1e-6);
            const int sx = int(inSrc.x());
            if (sx < 0 || sx >= src.width) continue;
            ++checked;
            // Diffuse surfaces look the same from both cameras (within texture aliasing).
            double diff = 0, norm = 1e-6;
            for (int c = 0; c < 3; ++c) {
                diff += std::abs(ref.at(x, y)[c] - src.at(sx, y)[c]);
                norm += ref.at(x, y)[c];
            }
            agree += diff / norm < 0.15;
        }
    ASSERT_GT(checked, 50);
    EXPECT_GT(agree, 0.75 * checked);
}

// The pictures are HDR in the EXRs and clipped at 1 in the 8-bit sRGB PNGs. Some of the
// first few training examples see a lamp or panel in ref; there the EXR exceeds 1 and the PNG
// is white, and everywhere the PNG is the EXR's sRGB value to 8 bits.
TEST(SynthDataset, PngClipsAtOneWhereTheExrShowsAVisibleLamp) {
    const fs::path dir = freshDir("clip");
    const SynthOptions o = smallOptions(dir.string());
    PanoramaLibrary panoramas(o.hdriDir);
    bool sawEmitter = false;
    for (uint64_t index = 0; index < 8 && !sawEmitter; ++index) {
        const fs::path x = dir / std::to_string(index);
        writeExample(exampleSeed("train", index), x.string(), o, panoramas);
        const ImageRGB exr = readImage((x / "ref.exr").string()),
                       png = readImage((x / "ref.png").string());
        ASSERT_EQ(exr.pixels.size(), png.pixels.size());
        std::size_t brightest = 0;
        for (std::size_t i = 0; i < exr.pixels.size(); ++i) {
            const float v = exr.pixels[i];
            if (v > exr.pixels[brightest]) brightest = i;
            if (v >= 1.f)
                ASSERT_EQ(png.pixels[i], 1.f) << i;
            else
                ASSERT_NEAR(srgbEncode(png.pixels[i]), srgbEncode(std::max(v, 0.f)), 0.51 / 255)
                    << i;
        }
        if (exr.pixels[brightest] < 2.f) continue;
        // The brightest pixel shows an emitter: a lamp, a panel or a window.
        const Scene scene = loadScene((x / "scene.json").string());
        const CamerasFile cams = loadCamerasFile((x / "cameras.json").string());
        const int px = int(brightest / 3 % exr.width), py = int(brightest / 3 / exr.width);
        const RayTracer tracer(scene);
        BakeOptions cheap;
        cheap.maxTexels = 500;
        cheap.gatherRays = 1;
        cheap.lightSamples = 1;
        cheap.bounces = 0;
        const RadianceField field(scene, tracer, panoramas, cheap);
        for (int dy = -1; dy <= 1; ++dy)  // the emitter may cover only part of the pixel
            for (int dx = -1; dx <= 1; ++dx) {
                const RayHit hit = tracer.intersect(
                    cams.ref.position,
                    cams.ref.pixelDirection(px + 0.5 + 0.5 * dx, py + 0.5 + 0.5 * dy), 0.0);
                sawEmitter |= hit.hit && field.isEmitting(hit.point);
            }
    }
    EXPECT_TRUE(sawEmitter);
}

}  // namespace
}  // namespace lh::synth
