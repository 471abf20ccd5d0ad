// The data-set reader on a dev_cycles-style example made here: cameras.json with Blender's
// extra fields, views, envmaps with their first-hit positions, a one-channel z-depth EXR, and
// no env_K_mask.png for the first envmap (computed) but one for the second (read).
#include "net/training_data.h"
#include "net/exposure_filter.h"

#include "core/atomic_file.h"
#include "core/errors.h"
#include "image/image_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace lh::net {
namespace {

struct ScratchDir {
    fs::path path;
    explicit ScratchDir(const std::string& name)
        : path(fs::temp_directory_path() /
               ("lh_training_data_" + std::to_string(::getpid()) + "_" + name)) {
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~ScratchDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

// As dev_cycles writes it: a camera with image/depth file names, scene name, baseline,
// envmap size and per-envmap clearance, none of which the reader needs.
const char* kCamerasJson = R"({
 "scene": "07", "world_frame": "reference camera, OpenCV axes, meters",
 "ref": {"width": 40, "height": 30, "fx": 20.0, "fy": 20.0, "cx": 20.0, "cy": 15.0,
         "cam_to_world": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]],
         "image": "ref.exr", "image_png": "ref.png", "depth": "ref_depth.exr"},
 "src": {"width": 40, "height": 30, "fx": 20.0, "fy": 20.0, "cx": 20.0, "cy": 15.0,
         "cam_to_world": [[1,0,0,0.1],[0,1,0,0],[0,0,1,0],[0,0,0,1]],
         "image": "src.exr", "image_png": "src.png"},
 "tgt": {"width": 40, "height": 30, "fx": 20.0, "fy": 20.0, "cx": 20.0, "cy": 15.0,
         "cam_to_world": [[1,0,0,-0.1],[0,1,0,0],[0,0,1,0],[0,0,0,1]],
         "image": "tgt.exr", "image_png": "tgt.png"},
 "near": 1.9, "far": 4.1, "median_ref_depth": 3.0, "baseline": 0.1,
 "envmap_width": 8, "envmap_height": 4,
 "envmaps": [
  {"position": [0.1, 0.2, 1.0], "file": "env_0.exr", "position_file": "env_0_pos.exr", "clearance": 0.4},
  {"position": [-0.3, 0.1, 1.5], "file": "env_1.exr", "position_file": "env_1_pos.exr", "clearance": 0.6}
 ]
})";

// z-depth as dev_cycles stores it: one HALF channel named Y. Columns 0..19 see a screen at
// 2 m, columns 20..39 a wall at 4 m.
void writeDepthY(const fs::path& path) {
    const int width = 40, height = 30;
    std::vector<half> depth(std::size_t(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            depth[std::size_t(y) * width + x] = half(x < 20 ? 2.f : 4.f);
    const Imath::Box2i window(Imath::V2i(0, 0), Imath::V2i(width - 1, height - 1));
    Imf::Header header(window, window);
    header.channels().insert("Y", Imf::Channel(Imf::HALF));
    Imf::FrameBuffer frame;
    frame.insert("Y", Imf::Slice::Make(Imf::HALF, depth.data(), window));
    Imf::OutputFile file(path.string().c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(height);
}

// An 8x4 map whose left half (columns 0..3) holds `left` and right half `right`.
ImageRGB halves(const Vec3d& left, const Vec3d& right) {
    ImageRGB image(8, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c) image.at(x, y)[c] = float(x < 4 ? left[c] : right[c]);
    return image;
}

// The example: env_0 sees the visible wall (0.5, 0.2, 4) on its left half and the wall behind
// the screen (-1, 0, 4) on its right half; env_1 ships a mask with only pixel (0, 0) set.
fs::path writeExample(const fs::path& root, bool withDepth = true) {
    const fs::path dir = root / "07";
    fs::create_directories(dir);
    writeTextFile((dir / "cameras.json").string(), kCamerasJson);
    ImageRGB view(40, 30);
    std::fill(view.pixels.begin(), view.pixels.end(), 0.2f);
    for (const char* name : {"ref.png", "src.png", "tgt.png"})
        writePng(view, (dir / name).string());
    writeExr(halves({3.f, 2.f, 1.f}, {0.5f, 0.5f, 0.5f}), (dir / "env_0.exr").string());
    writeExr(halves({1.f, 1.f, 1.f}, {1.f, 1.f, 1.f}), (dir / "env_1.exr").string());
    writeExr(halves({0.5, 0.2, 4.0}, {-1.0, 0.0, 4.0}), (dir / "env_0_pos.exr").string());
    writeExr(halves({0.5, 0.2, 4.0}, {0.5, 0.2, 4.0}), (dir / "env_1_pos.exr").string());
    ImageRGB mask(8, 4);
    std::fill_n(mask.at(0, 0), 3, 1.f);
    writePng(mask, (dir / "env_1_mask.png").string());
    if (withDepth) writeDepthY(dir / "ref_depth.exr");
    return dir;
}

TEST(ExposureFilter, LeavesOutScenesWithAnEnvmapClippedOnMoreThanTheLimit) {
    // env_0's left half has a channel mean of 2 (clipped), its right half 0.5; env_1 is 1
    // everywhere, which is not above 1.
    EXPECT_EQ(clippedFraction(halves({3.f, 2.f, 1.f}, {0.5f, 0.5f, 0.5f})), 0.5);
    EXPECT_EQ(clippedFraction(halves({1.f, 1.f, 1.f}, {1.f, 1.f, 1.f})), 0.0);
    EXPECT_EQ(clippedFraction(ImageRGB()), 0.0);
    ScratchDir bright("filter_bright"), dim("filter_dim");
    const std::string brightScene = writeExample(bright.path).string();
    const fs::path dimScene = writeExample(dim.path);
    writeExr(halves({0.5f, 0.5f, 0.5f}, {0.9f, 0.9f, 0.9f}), (dimScene / "env_0.exr").string());
    const std::vector<std::string> both = {brightScene, dimScene.string()};
    std::ostringstream progress;
    // The worst envmap decides: 0.5 of env_0's pixels.
    EXPECT_EQ(withoutOverexposedScenes(both, 0.5, progress), both);
    EXPECT_EQ(withoutOverexposedScenes(both, 0.49, progress),
              std::vector<std::string>{dimScene.string()});
    EXPECT_EQ(withoutOverexposedScenes(both, 0.0, progress),
              std::vector<std::string>{dimScene.string()});
    EXPECT_NE(progress.str().find("2/2 scenes, 1 kept"), std::string::npos) << progress.str();
    fs::remove(dimScene / "env_1.exr");
    EXPECT_THROW(withoutOverexposedScenes(both, 0.1, progress), FileError);
}

TEST(TrainingData, ReadsADevCyclesStyleExampleAndComputesMissingMasks) {
    ScratchDir scratch("dev_cycles");
    const fs::path dir = writeExample(scratch.path);
    EXPECT_EQ(listExamples(scratch.path.string()), std::vector<std::string>{dir.string()});

    const TrainingExample ex = loadExample(dir.string(), /*withMasks=*/true);
    ASSERT_EQ(ex.envmaps.size(), 2u);
    ASSERT_EQ(ex.cameras.envmaps.size(), 2u);
    EXPECT_EQ(ex.cameras.envmaps[0].position, Vec3d(0.1, 0.2, 1.0));
    EXPECT_EQ(ex.cameras.envmaps[1].position, Vec3d(-0.3, 0.1, 1.5));
    EXPECT_EQ(ex.cameras.envmaps[0].positionFile, "env_0_pos.exr");
    EXPECT_DOUBLE_EQ(*ex.cameras.near, 1.9);
    EXPECT_DOUBLE_EQ(ex.cameras.src->position.x(), 0.1);
    EXPECT_EQ(ex.envmaps[0].width, 8);
    EXPECT_FLOAT_EQ(ex.envmaps[0].at(0, 0)[0], 3.f);  // linear HDR, as written
    EXPECT_EQ(ex.ref.width, 40);

    ASSERT_EQ(ex.masks.size(), 2u);
    std::vector<std::uint8_t> leftHalf(32, 0), onlyFirst(32, 0);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) leftHalf[std::size_t(y) * 8 + x] = 1;
    onlyFirst[0] = 1;
    EXPECT_EQ(ex.masks[0], leftHalf);   // computed: the right half lies behind the screen
    EXPECT_EQ(ex.masks[1], onlyFirst);  // shipped: read as it is, not recomputed
}

// The views' EXR renders hold a lamp of 4 at pixel (0, 0) that the PNGs clip to 1: training
// exposes those, so that a darker exposure still clips the lamp (tests/net/
// training_inputs_test.cpp has the augmentation's side).
TEST(TrainingData, UnclippedViewsReplaceThePngsWhereAllThreeExist) {
    ScratchDir scratch("unclipped");
    const fs::path dir = writeExample(scratch.path);
    ImageRGB png(40, 30), exr(40, 30);
    std::fill(png.pixels.begin(), png.pixels.end(), 0.2f);
    std::fill(exr.pixels.begin(), exr.pixels.end(), 0.2f);
    std::fill_n(png.at(0, 0), 3, 1.f);
    std::fill_n(exr.at(0, 0), 3, 4.f);
    for (const char* view : {"ref", "src", "tgt"}) {
        writePng(png, (dir / (std::string(view) + ".png")).string());
        writeExr(exr, (dir / (std::string(view) + ".exr")).string());
    }
    EXPECT_EQ(missingUnclippedView(dir.string()), "");
    TrainingExample ex = loadExample(dir.string());
    EXPECT_FLOAT_EQ(ex.ref.at(0, 0)[0], 1.f);  // what predict and eval see
    ASSERT_TRUE(useUnclippedViews(ex));
    for (const ImageRGB* view : {&ex.ref, &ex.src, &ex.tgt}) {
        EXPECT_FLOAT_EQ(view->at(0, 0)[0], 4.f);
        EXPECT_FLOAT_EQ(view->at(5, 5)[1], 0.2f);
    }

    // Without all three EXRs, with one of another size, or with a NaN, the PNG views stay.
    ImageRGB broken = exr;
    broken.at(3, 3)[1] = std::numeric_limits<float>::quiet_NaN();
    writeExr(broken, (dir / "src.exr").string());
    TrainingExample withNan = loadExample(dir.string());
    EXPECT_FALSE(useUnclippedViews(withNan));
    EXPECT_FLOAT_EQ(withNan.ref.at(0, 0)[0], 1.f);
    fs::remove(dir / "tgt.exr");
    EXPECT_EQ(missingUnclippedView(dir.string()), "tgt.exr");
    TrainingExample partial = loadExample(dir.string());
    EXPECT_FALSE(useUnclippedViews(partial));
    EXPECT_FLOAT_EQ(partial.ref.at(0, 0)[0], 1.f);
    // Reading only the pair (as eval does), the target's render is not needed.
    writeExr(exr, (dir / "src.exr").string());
    EXPECT_EQ(missingUnclippedView(dir.string(), UnclippedViews::RefAndSrc), "");
    TrainingExample pairOnly = loadExample(dir.string());
    ASSERT_TRUE(useUnclippedViews(pairOnly, UnclippedViews::RefAndSrc));
    EXPECT_FLOAT_EQ(pairOnly.ref.at(0, 0)[0], 4.f);
    EXPECT_FLOAT_EQ(pairOnly.src.at(0, 0)[0], 4.f);
    EXPECT_FLOAT_EQ(pairOnly.tgt.at(0, 0)[0], 1.f);
    writeExr(ImageRGB(20, 15), (dir / "tgt.exr").string());
    EXPECT_FALSE(useUnclippedViews(partial));
    EXPECT_FLOAT_EQ(partial.ref.at(0, 0)[0], 1.f);
    EXPECT_FLOAT_EQ(partial.tgt.at(0, 0)[0], 1.f);
}

TEST(TrainingData, WithoutMasksNeedsNeitherPositionsNorDepth) {
    ScratchDir scratch("no_masks");
    const fs::path dir = writeExample(scratch.path, /*withDepth=*/false);
    const TrainingExample ex = loadExample(dir.string());
    EXPECT_EQ(ex.envmaps.size(), 2u);
    EXPECT_TRUE(ex.masks.empty());
}

TEST(TrainingData, SaysWhatIsMissingWhenNoMaskCanBeMade) {
    ScratchDir scratch("missing_depth");
    const fs::path dir = writeExample(scratch.path, /*withDepth=*/false);
    try {
        loadExample(dir.string(), /*withMasks=*/true);
        FAIL() << "an example without masks nor depth was accepted";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("env_0_mask.png"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("ref_depth.exr"), std::string::npos) << e.what();
    }
}

// The real development set, where this machine has it: every scene reads, with one mask per
// envmap that is neither empty nor full, and the pixel looking straight back (-z, column 0,
// towards the wall behind the reference camera) unobserved.
TEST(TrainingData, ReadsTheDevCyclesSetWhereItIsInstalled) {
    const fs::path root = fs::path(LIGHTHOUSE_SOURCE_DIR) / ".." / "shared" / "data" / "dev_cycles";
    if (!fs::is_directory(root)) GTEST_SKIP() << root << " is not on this machine";
    const std::vector<std::string> dirs = listExamples(root.string());
    EXPECT_EQ(dirs.size(), 12u);
    for (const std::string& dir : dirs) {
        const TrainingExample ex = loadExample(dir, /*withMasks=*/true);
        ASSERT_EQ(ex.masks.size(), ex.envmaps.size()) << dir;
        EXPECT_GE(ex.envmaps.size(), 1u) << dir;
        for (std::size_t k = 0; k < ex.masks.size(); ++k) {
            const std::vector<std::uint8_t>& mask = ex.masks[k];
            const double observed =
                double(std::count(mask.begin(), mask.end(), 1)) / double(mask.size());
            EXPECT_GT(observed, 0.02) << dir << " envmap " << k;
            EXPECT_LT(observed, 0.98) << dir << " envmap " << k;
            const int width = ex.envmaps[k].width, height = ex.envmaps[k].height;
            EXPECT_EQ(mask[std::size_t(height / 2) * width], 0) << dir << " envmap " << k;
        }
    }
}

}  // namespace
}  // namespace lh::net
