// Running COLMAP on two photos. COLMAP is optional (Debian's `colmap` package): without it the
// pose test is skipped, and the missing program must be one clear error.
#include "cameras/colmap_runner.h"
#include "cameras/colmap_convert.h"
#include "cameras/colmap_model.h"
#include "core/errors.h"
#include "synth/dataset.h"
#include "tests/support/temp_path.h"

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace lh {
namespace {

namespace fs = std::filesystem;

TEST(ColmapRunner, MissingColmapIsOneClearError) {
    ColmapRunOptions o;
    o.executable = "lighthouse-no-such-colmap";
    try {
        runColmapOnPair("a.jpg", "b.jpg", o);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("'lighthouse-no-such-colmap' not found"),
                  std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("apt-get install colmap"), std::string::npos);
    }
}

TEST(ColmapRunner, FindsExecutablesOnPath) {
    EXPECT_FALSE(findExecutable("sh").empty());
    EXPECT_TRUE(findExecutable("lighthouse-no-such-program").empty());
    EXPECT_TRUE(findExecutable("/no/such/dir/colmap").empty());
}

double angleDegrees(const Vec3d& a, const Vec3d& b) {
    const double c = a.dot(b) / (a.length() * b.length());
    return std::acos(std::max(-1.0, std::min(1.0, c))) * 180.0 / M_PI;
}

double rotationDegrees(const Mat3d& r) {
    const double c = (r(0, 0) + r(1, 1) + r(2, 2) - 1) / 2;
    return std::acos(std::max(-1.0, std::min(1.0, c))) * 180.0 / M_PI;
}

// What one COLMAP run on the pair gave back, against the truth.
struct PoseCheck {
    bool ok = false;
    std::string failure;  // why it is not within the bounds; empty when ok
};

// A synthetic scene's ref and src (640x480, true baseline ~0.1 m at 2..7 m) given to COLMAP with
// the true focal length must give back the true relative pose. COLMAP seeds RANSAC from the
// clock in its worker threads, so the answer varies between runs. Over 70 runs here it was
// mostly within 0.07 deg (near 1.69-1.72 against the true 1.64), now and then 2.3 deg off
// (near 0.95), and twice outside the bounds: near 0.35 (a baseline direction 15 deg off), and
// no model. So a run outside the bounds is retried twice: a pose that comes out wrong three
// times in a row fails.
PoseCheck runPairAgainstTruth(const std::string& example, const CamerasFile& truth) {
    auto fail = [](const std::string& why) { return PoseCheck{false, why}; };
    ColmapRunOptions o;
    o.fx = truth.ref.fx;
    ColmapPairOptions p;
    p.baseline = (truth.src->position - truth.ref.position).length();
    ColmapPairResult r;
    try {
        const ColmapRunResult run = runColmapOnPair(example + "/ref.png", example + "/src.png", o);
        p.ref = run.refName;
        p.src = run.srcName;
        r = convertColmapPair(readColmapModel(run.modelDir), p);
        fs::remove_all(run.workDir);
    } catch (const std::exception& e) {
        return fail(std::string("no cameras: ") + e.what());
    }
    if (!r.cameras.src) return fail("no src camera");
    const PinholeCamera& src = *r.cameras.src;
    const Mat3d relative = src.rotation.transpose() * truth.src->rotation;
    const double rotationError = rotationDegrees(relative);
    const double directionError = angleDegrees(src.position, truth.src->position);
    const double nearRatio = r.cameras.near.value_or(0) / truth.near.value_or(1);
    const double farRatio = r.cameras.far.value_or(0) / truth.far.value_or(1);
    char line[256];
    std::snprintf(line, sizeof line,
                  "rotation error %.3f deg, baseline direction error %.3f deg, baseline %.4f "
                  "(true %.4f), near / true near %.3f, far / true far %.3f",
                  rotationError, directionError, src.position.length(), *p.baseline, nearRatio,
                  farRatio);
    std::printf("%s\n", line);
    const bool ok = rotationError < 3.0 && directionError < 15.0 &&
                    std::abs(src.position.length() - *p.baseline) < 1e-9 && nearRatio > 0.5 &&
                    farRatio > 0 && farRatio < 2.0;
    return ok ? PoseCheck{true, ""} : fail(line);
}

TEST(ColmapRunner, SyntheticPairGivesBackTheTruePose) {
    if (findExecutable("colmap").empty()) GTEST_SKIP() << "colmap is not installed";
    synth::SynthOptions s;
    s.seed = 3;
    s.count = 1;
    s.width = 640;
    s.height = 480;
    s.envWidth = 32;
    s.envHeight = 16;
    s.envmapsPerExample = 1;
    s.hdriDir = std::string(LIGHTHOUSE_SOURCE_DIR) + "/synth/hdri";
    s.out = test::uniqueTempPath("colmap_synth");
    fs::remove_all(s.out);
    synth::writeDataset(s);
    const std::string example = s.out + "/000000";
    const CamerasFile truth = loadCamerasFile(example + "/cameras.json");
    ASSERT_TRUE(truth.src && truth.near && truth.far);

    std::vector<std::string> failures;
    for (int attempt = 0; attempt < 3; ++attempt) {
        const PoseCheck check = runPairAgainstTruth(example, truth);
        if (check.ok) break;
        failures.push_back(check.failure);
    }
    fs::remove_all(s.out);
    EXPECT_LT(failures.size(), 3u) << "three runs out of bounds; the last: " << failures.back();
}

TEST(ColmapRunner, UnrelatedPhotosAreRefused) {
    if (findExecutable("colmap").empty()) GTEST_SKIP() << "colmap is not installed";
    const std::string demo = std::string(LIGHTHOUSE_SOURCE_DIR) + "/data/demo_pair/ref.png";
    // A flat grey photo of the same size: no features, so no model can hold both.
    const std::string flat = test::uniqueTempPath("flat.png");
    const std::vector<unsigned char> grey(320 * 240 * 3, 128);
    ASSERT_TRUE(stbi_write_png(flat.c_str(), 320, 240, 3, grey.data(), 320 * 3));
    ColmapRunOptions o;
    o.fx = 266.0;
    try {
        runColmapOnPair(demo, flat, o);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("could not relate the two photos"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace lh
