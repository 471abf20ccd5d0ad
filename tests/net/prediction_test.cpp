// `predict` end to end through the torch-free Predictor, and the prediction path's hard
// cases: black, saturated and identical images, tiny baselines, and inputs that must be
// refused with a clear error (zero baseline, NaN pixels, sizes that disagree with the cameras).
#include "core/errors.h"
#include "image/luminance.h"
#include "net/lighthouse_net.h"
#include "net/predictor.h"
#include "render/envmap.h"
#include "render/radial_shell.h"
#include "render/render_volume.h"
#include "tests/net/net_test_scenes.h"

#include "tests/support/temp_path.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace lh::net {
namespace {

using test::planeCamera;
using test::renderPlane;

class PredictionTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        torch::manual_seed(5);
        LighthouseNet net(test::tinyConfig());
        modelPath() = test::uniqueTempPath("lighthouse_prediction_test.pt");
        saveModel(net, modelPath());
    }
    static void TearDownTestSuite() { std::filesystem::remove(modelPath()); }
    static std::string& modelPath() {
        static std::string path;
        return path;
    }

    // A model of `config` with seeded random weights, saved to a fresh temporary path.
    static std::string savedModel(const NetConfig& config, const std::string& name) {
        torch::manual_seed(5);
        LighthouseNet net(config);
        const std::string path = test::uniqueTempPath(name);
        saveModel(net, path);
        return path;
    }

    // A linear (EXR) pair of a wall four times brighter than white: an HDR model's volume of
    // it has voxels above white, and below it where the model invents darker colours.
    static StereoPair brightPlanePair() {
        StereoPair pair = planePair(0.2);
        for (float& v : pair.ref.pixels) v *= 4.f;
        for (float& v : pair.src.pixels) v *= 4.f;
        return pair;
    }

    static StereoPair planePair(double baseline) {
        StereoPair pair;
        pair.cameras.ref = planeCamera(64, 32);
        pair.cameras.src = planeCamera(64, 32, Vec3d(baseline, 0.0, 0.0));
        pair.ref = renderPlane(pair.cameras.ref, 2.0);
        pair.src = renderPlane(*pair.cameras.src, 2.0);
        return pair;
    }

    // Every stored value finite, and envmaps rendered from the volume finite too.
    static void expectFinitePrediction(const Prediction& p) {
        EXPECT_TRUE(std::isfinite(p.range.near) && std::isfinite(p.range.far) &&
                    p.range.far > p.range.near);
        for (const auto& level : p.volume.levels) {
            for (auto it = level.density->cbeginValueOn(); it; ++it)
                EXPECT_TRUE(std::isfinite(*it) && *it >= 0);
            for (auto it = level.color->cbeginValueOn(); it; ++it)
                EXPECT_TRUE(std::isfinite((*it)[0]) && std::isfinite((*it)[1]) &&
                            std::isfinite((*it)[2]));
        }
        EnvmapOptions options;
        options.width = 32;
        options.height = 16;
        const ImageRGB env = renderEnvmap(RenderVolume(p.volume), Vec3d(0, 0, 1), options);
        for (float v : env.pixels) EXPECT_TRUE(std::isfinite(v));
    }

    Predictor predictor{PredictorOptions{modelPath(), "cpu", 2, ""}};
};

TEST_F(PredictionTest, PredictsAVolumeInTheLayoutOfTheDepthRange) {
    StereoPair pair = planePair(0.2);
    pair.cameras.near = 1.0;
    pair.cameras.far = 4.0;
    const Prediction p = predictor.predict(pair);
    EXPECT_FALSE(p.rangeEstimated);
    ASSERT_TRUE(p.volume.layout.has_value());
    EXPECT_EQ(p.volume.layout->levels, 2);
    EXPECT_EQ(p.volume.layout->resolution, 16);
    EXPECT_DOUBLE_EQ(p.volume.layout->s0, 8.0);  // 2 min(far, 20)
    EXPECT_EQ(p.mpi.planeCount(), 16);
    EXPECT_NEAR(p.mpi.planeDepths.front(), 4.0, 1e-9);
    EXPECT_NEAR(p.mpi.planeDepths.back(), 1.0, 1e-9);
    expectFinitePrediction(p);
}

TEST_F(PredictionTest, EstimatesTheDepthRangeWhenCamerasGiveNone) {
    const Prediction p = predictor.predict(planePair(0.2));
    EXPECT_TRUE(p.rangeEstimated);
    EXPECT_FALSE(p.range.fallback);
    EXPECT_LT(p.range.near, 2.0);
    EXPECT_GT(p.range.far, 2.0);
    expectFinitePrediction(p);
}

TEST_F(PredictionTest, BlackAndSaturatedImagesGiveFiniteVolumes) {
    for (float value : {0.f, 1.f}) {
        StereoPair pair = planePair(0.2);
        std::fill(pair.ref.pixels.begin(), pair.ref.pixels.end(), value);
        std::fill(pair.src.pixels.begin(), pair.src.pixels.end(), value);
        const Prediction p = predictor.predict(pair);
        EXPECT_TRUE(p.range.fallback) << "a textureless pair cannot vote for a depth";
        EXPECT_DOUBLE_EQ(p.range.near, kFallbackNear);
        expectFinitePrediction(p);
    }
}

TEST_F(PredictionTest, IdenticalImagesAndTinyBaselinesGiveFiniteVolumes) {
    StereoPair same = planePair(0.2);
    same.src = same.ref;  // zero disparity everywhere: the scene looks infinitely far
    expectFinitePrediction(predictor.predict(same));
    expectFinitePrediction(predictor.predict(planePair(1e-7)));
}

TEST_F(PredictionTest, ImpossibleInputsAreRefusedWithAClearError) {
    StereoPair zero = planePair(0.0);
    EXPECT_THROW(predictor.predict(zero), InputError);
    StereoPair nan = planePair(0.2);
    nan.ref.pixels[10] = std::nanf("");
    EXPECT_THROW(predictor.predict(nan), InputError);
    StereoPair wrongSize = planePair(0.2);
    wrongSize.cameras.ref.width = 128;
    EXPECT_THROW(predictor.predict(wrongSize), InputError);
    StereoPair noSrc = planePair(0.2);
    noSrc.cameras.src.reset();
    EXPECT_THROW(predictor.predict(noSrc), InputError);
}

TEST_F(PredictionTest, PrunesAtTheThresholdTheModelWasTrainedUnderUnlessToldOtherwise) {
    EXPECT_FLOAT_EQ(predictor.pruneAlpha(), kDefaultPruneAlpha);  // a model trained unpruned
    NetConfig config = test::tinyConfig();
    config.pruneAlpha = 0.4;
    const std::string path = savedModel(config, "lighthouse_prediction_pruned.pt");
    const Predictor ownThreshold(PredictorOptions{path, "cpu", 2, ""});
    PredictorOptions keepAll{path, "cpu", 2, ""};
    keepAll.pruneAlpha = 0;
    const Predictor unpruned(keepAll);
    std::filesystem::remove(path);
    EXPECT_FLOAT_EQ(ownThreshold.pruneAlpha(), 0.4f);
    EXPECT_FLOAT_EQ(unpruned.pruneAlpha(), 0.0f);

    const StereoPair pair = planePair(0.2);
    const Prediction pruned = ownThreshold.predict(pair), all = unpruned.predict(pair);
    ASSERT_TRUE(pruned.volume.layout.has_value());
    long long kept = 0;
    for (size_t k = 0; k < pruned.volume.levels.size(); ++k) {
        const double voxel = pruned.volume.layout->voxelSize(int(k));
        for (auto it = pruned.volume.levels[k].density->cbeginValueOn(); it; ++it, ++kept)
            EXPECT_GE(1 - std::exp(-double(*it) * voxel), 0.4 - 1e-4);
    }
    EXPECT_GT(kept, 0);
    EXPECT_GT(all.volume.activeVoxelCount(), std::size_t(kept));
}

TEST_F(PredictionTest, ShellKeepsTheEnvmapSeenFromItsCentre) {
    PredictorOptions shellOptions{modelPath(), "cpu", 2, ""};
    shellOptions.shell = true;
    const Predictor shelled(shellOptions);
    StereoPair pair = planePair(0.2);
    pair.cameras.near = 1.0;
    pair.cameras.far = 4.0;
    const Prediction fog = predictor.predict(pair), shell = shelled.predict(pair);
    expectFinitePrediction(shell);
    ASSERT_TRUE(shell.volume.layout.has_value());
    EXPECT_EQ(*shell.volume.layout, *fog.volume.layout);
    // The untrained network's fog fills the volume; the shell is a layer of it.
    EXPECT_LT(shell.volume.activeVoxelCount(), fog.volume.activeVoxelCount() / 2);
    EnvmapOptions options;
    options.width = 64;
    options.height = 32;
    const Vec3d centre = defaultShellCentre(*fog.volume.layout);
    const ImageRGB a = renderEnvmap(RenderVolume(fog.volume), centre, options);
    const ImageRGB b = renderEnvmap(RenderVolume(shell.volume), centre, options);
    double squared = 0, sum = 0, black = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        squared += double(a.pixels[i] - b.pixels[i]) * (a.pixels[i] - b.pixels[i]);
        black += double(a.pixels[i]) * a.pixels[i];
        sum += a.pixels[i];
    }
    const double n = double(a.pixels.size());
    // The same light up to the tiny model's 16^3 lattice, on which the layer is resampled
    // coarsely (0.14 here); a missing layer would be off by as much as a black envmap.
    EXPECT_LT(std::sqrt(squared / n) / (sum / n), 0.2);
    EXPECT_GT(std::sqrt(black / n) / (sum / n), 0.9);
}

TEST_F(PredictionTest, ShellKeepsThePredictedMediumTheReferenceCameraSees) {
    PredictorOptions shellOptions{modelPath(), "cpu", 2, ""};
    shellOptions.shell = true;
    StereoPair pair = planePair(0.2);
    pair.cameras.near = 1.0;
    pair.cameras.far = 4.0;
    const Prediction fog = predictor.predict(pair), shell = Predictor(shellOptions).predict(pair);
    ASSERT_TRUE(shell.volume.refCamera.has_value());
    const PinholeCamera& camera = *shell.volume.refCamera;
    // Every voxel of the prediction in the camera's view is in the shell as it was; of those
    // outside it, the shell keeps at most a layer.
    long long seen = 0, unseenBefore = 0, unseenAfter = 0;
    for (size_t k = 0; k < fog.volume.levels.size(); ++k) {
        const auto& level = fog.volume.levels[k];
        const auto& shellDensity = shell.volume.levels[k].density->tree();
        for (auto it = level.density->cbeginValueOn(); it; ++it) {
            const Vec3d p = level.transform().indexToWorld(it.getCoord());
            if (camera.projectIntoImage(p)) {
                ++seen;
                EXPECT_EQ(shellDensity.getValue(it.getCoord()), *it);
            } else {
                ++unseenBefore;
            }
        }
        for (auto it = shell.volume.levels[k].density->cbeginValueOn(); it; ++it)
            if (!camera.projectIntoImage(level.transform().indexToWorld(it.getCoord())))
                ++unseenAfter;
    }
    EXPECT_GT(seen, 1000);
    EXPECT_LT(unseenAfter, unseenBefore / 2);
}

// How many of a prediction's colour voxels lie above the knee, above white up to the knee, and
// at or below white.
struct VoxelLuminances {
    long long aboveKnee = 0, aboveWhiteUpToKnee = 0, atOrBelowWhite = 0;
};

// Checks every voxel of `expanded` against `plain`: above the knee its luminance is
// knee + gain (Y - knee); at or below the knee it is unchanged. Counts them.
VoxelLuminances expectExpandedAboveKnee(const Prediction& plain, const Prediction& expanded,
                                        double gain, double knee) {
    VoxelLuminances counts;
    for (size_t k = 0; k < plain.volume.levels.size(); ++k) {
        const auto& before = plain.volume.levels[k].color->tree();
        const auto& after = expanded.volume.levels[k].color->tree();
        for (auto it = before.cbeginValueOn(); it; ++it) {
            const openvdb::Vec3s c = *it, g = after.getValue(it.getCoord());
            const double y = rec709Luminance(c.asPointer());
            if (y > knee) {
                ++counts.aboveKnee;
                const double expected = knee + gain * (y - knee);
                EXPECT_NEAR(rec709Luminance(g.asPointer()), expected, 1e-3 * (1 + expected));
            } else {
                ++(y > 1.0 ? counts.aboveWhiteUpToKnee : counts.atOrBelowWhite);
                EXPECT_EQ(g, c);
            }
        }
    }
    return counts;
}

// The brightest luminance of a prediction's voxels.
double brightestVoxel(const Prediction& p) {
    double brightest = 0;
    for (const auto& level : p.volume.levels)
        for (auto it = level.color->cbeginValueOn(); it; ++it) {
            const openvdb::Vec3s c = *it;
            brightest = std::max(brightest, rec709Luminance(c.asPointer()));
        }
    return brightest;
}

TEST_F(PredictionTest, AModelWithAnEmitterHeadReportsTheLampsItPlaced) {
    NetConfig config = test::tinyHdrConfig();
    config.emitters = 3;
    const std::string path = savedModel(config, "lighthouse_prediction_emitters.pt");
    StereoPair pair = planePair(0.2);
    pair.cameras.near = 1.0;
    pair.cameras.far = 4.0;
    const Prediction lamps = Predictor(PredictorOptions{path, "cpu", 2, ""}).predict(pair);
    std::filesystem::remove(path);
    expectFinitePrediction(lamps);
    EXPECT_TRUE(predictor.predict(pair).emitters.empty());  // a model without the head
    ASSERT_EQ(lamps.emitters.size(), 3u);
    const double half = lamps.volume.layout->side(0) / 2;
    for (const PredictedEmitter& e : lamps.emitters) {
        // A fresh head: every lamp as dim (opacity sigmoid(-4)), inside level 0, a radius in
        // the head's range and a positive colour.
        EXPECT_NEAR(e.alpha, 1.0 / (1.0 + std::exp(4.0)), 1e-6);
        EXPECT_LT(std::abs(e.position.x()), half);
        EXPECT_LT(std::abs(e.position.y()), half);
        EXPECT_LT(std::abs(e.position.z()), half);
        EXPECT_GE(e.radius, kMinEmitterRadius);
        EXPECT_LE(e.radius, kMaxEmitterRadius);
        EXPECT_GT(e.radiance.x(), 0.0);
    }
}

TEST_F(PredictionTest, HighlightGainBrightensOnlyVoxelsAboveWhite) {
    const std::string path = savedModel(test::tinyHdrConfig(), "lighthouse_prediction_hdr.pt");
    const StereoPair pair = brightPlanePair();
    PredictorOptions plainOptions{path, "cpu", 2, ""}, gained = plainOptions;
    gained.highlightGain = 20.0;
    const Prediction plain = Predictor(plainOptions).predict(pair),
                     bright = Predictor(gained).predict(pair);
    std::filesystem::remove(path);
    expectFinitePrediction(bright);
    const VoxelLuminances counts = expectExpandedAboveKnee(plain, bright, 20.0, 1.0);
    EXPECT_GT(counts.aboveKnee, 0) << "the test pair gave no voxel above white";
    EXPECT_GT(counts.atOrBelowWhite, 0);
}

TEST_F(PredictionTest, AHighlightKneeLeavesTheVoxelsBelowItAsTheyWere) {
    const std::string path = savedModel(test::tinyHdrConfig(), "lighthouse_prediction_knee.pt");
    const StereoPair pair = brightPlanePair();
    PredictorOptions plainOptions{path, "cpu", 2, ""}, kneed = plainOptions;
    const Prediction plain = Predictor(plainOptions).predict(pair);
    // Halfway between white and the brightest voxel: voxels on both sides of the knee.
    const double knee = 0.5 * (1.0 + brightestVoxel(plain));
    ASSERT_GT(knee, 1.0) << "the test pair gave no voxel above white";
    kneed.highlightGain = 20.0;
    kneed.highlightKnee = knee;
    const Predictor predictor(kneed);
    EXPECT_DOUBLE_EQ(predictor.highlightKnee(), knee);
    const Prediction bright = predictor.predict(pair);
    std::filesystem::remove(path);
    expectFinitePrediction(bright);
    const VoxelLuminances counts = expectExpandedAboveKnee(plain, bright, 20.0, knee);
    EXPECT_GT(counts.aboveKnee, 0);
    EXPECT_GT(counts.aboveWhiteUpToKnee, 0) << "no voxel between white and the knee";
}

TEST_F(PredictionTest, AppliesTheHighlightGainTheModelWasTrainedUnderUnlessToldOtherwise) {
    EXPECT_DOUBLE_EQ(predictor.highlightGain(), 1.0);  // a model trained without one
    NetConfig config = test::tinyHdrConfig();
    config.highlightGain = 20.0;
    const std::string path = savedModel(config, "lighthouse_prediction_gained.pt");
    PredictorOptions own{path, "cpu", 2, ""}, none = own, explicitGain = own;
    none.highlightGain = 1.0;
    explicitGain.highlightGain = 20.0;
    const Predictor ownGain(own), noGain(none), told(explicitGain);
    EXPECT_DOUBLE_EQ(ownGain.highlightGain(), 20.0);
    EXPECT_DOUBLE_EQ(noGain.highlightGain(), 1.0);
    const StereoPair pair = brightPlanePair();
    const Prediction a = ownGain.predict(pair), b = told.predict(pair), c = noGain.predict(pair);
    std::filesystem::remove(path);
    // The model's own gain is the explicit one: the same volume; without it, another.
    double same = 0, differ = 0;
    for (size_t k = 0; k < a.volume.levels.size(); ++k)
        for (auto it = a.volume.levels[k].color->cbeginValueOn(); it; ++it) {
            const openvdb::Vec3s x = *it;
            same += (x - b.volume.levels[k].color->tree().getValue(it.getCoord())).length();
            differ += (x - c.volume.levels[k].color->tree().getValue(it.getCoord())).length();
        }
    EXPECT_EQ(same, 0.0);
    EXPECT_GT(differ, 0.0);
}

TEST(PredictorOptionsTest, UnknownDeviceOrMissingModelIsAClearError) {
    EXPECT_THROW(Predictor(PredictorOptions{"/nonexistent/model.pt", "cpu", 1, ""}), FileError);
    EXPECT_THROW(Predictor(PredictorOptions{"", "tpu", 1, ""}), InputError);
    PredictorOptions dim{"", "cpu", 1, ""};
    dim.highlightGain = 0.5;
    EXPECT_THROW(Predictor{dim}, InputError);
    PredictorOptions wallsToo{"", "cpu", 1, ""};
    wallsToo.highlightKnee = 0.5;
    EXPECT_THROW(Predictor{wallsToo}, InputError);
}

}  // namespace
}  // namespace lh::net
