// `lighthouse train` on a tiny synthetic data set with oracles: a run interrupted and resumed
// ends with the weights of an uninterrupted run, direct supervision uses the oracle and the
// depth map, and the paper's mode trains without either.
#include "net/trainer.h"
#include "core/errors.h"
#include "net/lighthouse_net.h"
#include "synth/dataset.h"
#include "tests/net/net_test_scenes.h"
#include "tests/net/tiny_training_set.h"

#include "tests/support/temp_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace lh::net {
namespace {

namespace fs = std::filesystem;

class TrainerTest : public test::TinyTrainingSetTest {
protected:
    TrainOptions options(const std::string& name) const {
        TrainOptions o;
        o.data = dataDir();
        o.configOverride = test::tinyHdrConfig();
        o.out = test::uniqueTempPath(name + ".pt");
        o.iterations = 4;
        o.checkpointEvery = 100;
        o.validateEvery = 100;
        o.validationScenes = 1;
        o.logEvery = 1;
        o.threads = 1;
        o.seed = 3;
        o.averageDecay = 0.5;  // an average that moves within 4 steps, so resuming must restore it
        return o;
    }
    // options(name) for a model whose emitter head has the pretrainable photo classifier
    // ("+emitters+photo+cells", 3 lamps).
    TrainOptions photoCellsOptions(const std::string& name) const {
        TrainOptions o = options(name);
        NetConfig config = test::tinyHdrConfig();
        config.emitters = 3;
        config.emitterPhoto = config.emitterPhotoCells = true;
        o.configOverride = config;
        return o;
    }
    static void removeOutputs(const TrainOptions& o) {
        for (const std::string suffix : {"", ".csv", ".png", ".checkpoint"})
            fs::remove(o.out + suffix);
    }
    // Largest |difference| over the weights of two networks of one configuration; NaN (which
    // fails every comparison) after a test failure if their parameter lists differ.
    static double largestWeightDifference(const LighthouseNet& a, const LighthouseNet& b) {
        const auto pa = a->named_parameters(), pb = b->named_parameters();
        EXPECT_EQ(pa.size(), pb.size());
        if (pa.size() != pb.size()) return std::nan("");
        double largest = 0;
        for (const auto& p : pa)
            largest = std::max(largest, (p.value() - pb[p.key()]).abs().max().item<double>());
        return largest;
    }
    static double largestWeightDifference(const LighthouseNet& a, const std::string& modelPath) {
        return largestWeightDifference(a, loadModel(modelPath, torch::Device(torch::kCPU)));
    }
    // Trains two short runs of the same seed and data, `off` and `on` (full precision, no
    // moving average), whose options differ only by what `set(options, value)` sets, and
    // returns the largest difference of their weights; their files are removed.
    double weightChangeOf(const std::string& name, double off, double on,
                          const std::function<void(TrainOptions&, double)>& set,
                          std::ostream& log) const {
        const auto trained = [&](const std::string& suffix, double value) {
            TrainOptions o = options(name + suffix);
            o.averageDecay = 0.0;
            o.halfModel = false;
            set(o, value);
            train(o, log);
            return o;
        };
        const TrainOptions a = trained("_off", off), b = trained("_on", on);
        const double change =
            largestWeightDifference(loadModel(a.out, torch::Device(torch::kCPU)), b.out);
        removeOutputs(a);
        removeOutputs(b);
        return change;
    }
    static std::string readText(const std::string& path) {
        std::ifstream in(path);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }
};

TEST_F(TrainerTest, ExamplesCarryTheirOracle) {
    EXPECT_TRUE(fs::is_regular_file(fs::path(dataDir()) / "000000" / "oracle.vdb"));
    EXPECT_TRUE(fs::is_regular_file(fs::path(dataDir()) / "000000" / "depth.exr"));
}

TEST_F(TrainerTest, ResumingGivesTheWeightsOfAnUninterruptedRun) {
    std::ostringstream log;
    const TrainOptions whole = options("lighthouse_trainer_whole");
    train(whole, log);
    TrainOptions split = options("lighthouse_trainer_split");
    split.stopAfter = 2;
    train(split, log);
    EXPECT_FALSE(fs::exists(split.out + ".csv") &&
                 readText(split.out + ".csv").find("\n4,") != std::string::npos);
    ASSERT_TRUE(fs::is_regular_file(split.checkpointPath()));
    split.stopAfter = 0;
    train(split, log);  // resumes at 2
    EXPECT_NE(log.str().find("resuming from"), std::string::npos);

    LighthouseNet a = loadModel(whole.out, torch::Device(torch::kCPU));
    EXPECT_LT(largestWeightDifference(a, split.out), 1e-5)
        << "largest weight difference between the two runs";
    // The trained weights moved away from a fresh network's (the comparison is not vacuous).
    torch::manual_seed(3);
    LighthouseNet fresh(test::tinyHdrConfig());
    EXPECT_GT(largestWeightDifference(fresh, a), 1e-4);
    removeOutputs(whole);
    removeOutputs(split);
}

TEST_F(TrainerTest, TheModelWrittenIsTheAverageOfTheWeights) {
    // Decay 0: the last step's weights, moved from the fresh network's. A decay of nearly 1:
    // the average has not left the fresh network's weights in 4 steps.
    std::ostringstream log;
    TrainOptions last = options("lighthouse_trainer_last");
    last.averageDecay = 0.0;
    last.halfModel = false;  // float32 files: the comparison below is finer than half precision
    train(last, log);
    TrainOptions slow = options("lighthouse_trainer_slow_average");
    slow.averageDecay = 1.0 - 1e-9;
    slow.halfModel = false;
    train(slow, log);
    torch::manual_seed(3);
    LighthouseNet fresh(test::tinyHdrConfig());
    const double lastMoved = largestWeightDifference(fresh, last.out);
    EXPECT_GT(lastMoved, 1e-4);
    EXPECT_LT(largestWeightDifference(fresh, slow.out), 1e-3 * lastMoved);
    removeOutputs(last);
    removeOutputs(slow);
}

TEST_F(TrainerTest, TheEmitterHeadTrainsAtAHundredTimesTheLearningRate) {
    // Adam's first step moves every weight with a gradient by the learning rate exactly
    // (its sign times lr): the head's by 100 lr, the rest by lr.
    std::ostringstream log;
    TrainOptions o = options("lighthouse_trainer_emitters");
    NetConfig config = test::tinyHdrConfig();
    config.emitters = 3;
    o.configOverride = config;
    o.iterations = 1;
    o.averageDecay = 0.0;
    o.halfModel = false;
    train(o, log);
    torch::manual_seed(3);
    LighthouseNet fresh(config);
    const LighthouseNet trained = loadModel(o.out, torch::Device(torch::kCPU));
    removeOutputs(o);
    double head = 0, body = 0;
    const auto before = fresh->named_parameters();
    for (const auto& p : trained->named_parameters()) {
        const double moved = (p.value() - before[p.key()]).abs().max().item<double>();
        double& largest = p.key().rfind("emitter_head.", 0) == 0 ? head : body;
        largest = std::max(largest, moved);
    }
    const double lr = o.learningRate / 10;  // a one-iteration run is all in its last fifth
    EXPECT_NEAR(body, lr, 0.05 * lr);
    EXPECT_NEAR(head, 100 * lr, 5 * lr);
}

TEST_F(TrainerTest, TheIrradianceWeightSteersTraining) {
    // The same seed and data with the irradiance loss off and strong: the envmap stage's
    // gradients differ, so do the weights; a negative weight is refused.
    std::ostringstream log;
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_irradiance", 0.0, 4.0,
                  [](TrainOptions& o, double w) { o.irradianceWeight = w; }, log),
              1e-6)
        << "the irradiance weight changed nothing";
    TrainOptions negative = options("lighthouse_trainer_irradiance_negative");
    negative.irradianceWeight = -1.0;
    EXPECT_THROW(negative.validate(), InputError);
}

TEST_F(TrainerTest, AnUnclippedPhotoHeadTrainsOnTheRendersBeforeTheirClip) {
    // The tiny set's examples carry ref.exr: a "+unclipped" head reads it (exposed, not
    // clipped, not quantised), a plain photo head the photo made from it, so the same seed and
    // data train different weights.
    ASSERT_TRUE(fs::is_regular_file(fs::path(dataDir()) / "000000" / "ref.exr"));
    std::ostringstream log;
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_unclipped", 0.0, 1.0,
                  [](TrainOptions& o, double on) {
                      NetConfig config = test::tinyHdrConfig();
                      config.emitters = 3;
                      config.emitterPhoto = true;
                      config.emitterPhotoUnclipped = on > 0;
                      o.configOverride = config;
                      o.emitterCellWeight = 10;
                  },
                  log),
              1e-6)
        << "the head read the same photo either way";
}

TEST_F(TrainerTest, TheEmitterHeadsLossWeightsSteerTheHead) {
    // The tiny set's rooms have lamps in scene.json: with the lamp-position loss (a plain head),
    // the lamp-cell loss (a "+photo" head) or the lamp-light loss on, the head's gradients
    // differ, so do the weights, and the log names the term (the cell and light losses also
    // their values); a negative weight is refused.
    struct HeadLoss {
        const char* name;
        bool photoHead;
        double TrainOptions::*weight;
        std::vector<std::string> logged;
    };
    const HeadLoss losses[] = {
        {"position",
         false,
         &TrainOptions::emitterPositionWeight,
         {"emitter head also 10 x squared distance"}},
        {"cells",
         true,
         &TrainOptions::emitterCellWeight,
         {"emitter head also 10 x divergence of its cells", ", emitter cells "}},
        {"light",
         false,
         &TrainOptions::emitterLightWeight,
         {"emitter head also 10 x error of its lamps' axis irradiance against the envmaps' "
          "unobserved",
          ", emitter light "}}};
    for (const HeadLoss& loss : losses) {
        std::ostringstream log;
        const std::string name = std::string("lighthouse_trainer_emitter_") + loss.name;
        EXPECT_GT(weightChangeOf(
                      name, 0.0, 10.0,
                      [&](TrainOptions& o, double w) {
                          NetConfig config = test::tinyHdrConfig();
                          config.emitters = 3;
                          config.emitterPhoto = loss.photoHead;
                          o.configOverride = config;
                          o.*loss.weight = w;
                      },
                      log),
                  1e-6)
            << "the " << loss.name << " weight changed nothing";
        for (const std::string& text : loss.logged)
            EXPECT_NE(log.str().find(text), std::string::npos) << log.str();
        TrainOptions negative = options(name + "_negative");
        negative.*loss.weight = -1.0;
        EXPECT_THROW(negative.validate(), InputError) << loss.name;
    }
    // The light loss needs lamps to supervise: a model without a head is refused.
    TrainOptions headless = options("lighthouse_trainer_emitter_light_headless");
    headless.emitterLightWeight = 1.0;
    std::ostringstream refused;
    EXPECT_THROW(train(headless, refused), InputError);
}

TEST_F(TrainerTest, PretrainingTheLampCellsComesBeforeAFreshRunOnly) {
    // A "+cells" run pretrains the head's photo classifier on the 2 training photos (one of the
    // 3 is held out) before its first step; resumed from its checkpoint it does not again. A
    // configuration without the classifier is refused.
    TrainOptions o = photoCellsOptions("lighthouse_trainer_lamp_cells");
    o.iterations = 1;
    o.pretrainLampCellEpochs = 2;
    std::ostringstream first, second;
    train(o, first);
    EXPECT_NE(first.str().find("lamp cells from photos alone, 2 photos"), std::string::npos)
        << first.str();
    EXPECT_NE(first.str().find("lamp cells, epoch 2/2"), std::string::npos) << first.str();
    o.iterations = 2;
    train(o, second);
    EXPECT_NE(second.str().find("resuming"), std::string::npos) << second.str();
    EXPECT_EQ(second.str().find("lamp cells from photos alone"), std::string::npos) << second.str();
    removeOutputs(o);
    TrainOptions plain = options("lighthouse_trainer_lamp_cells_plain");
    plain.pretrainLampCellEpochs = 2;
    EXPECT_THROW(train(plain, second), InputError);
    plain.pretrainLampCellEpochs = -1;
    EXPECT_THROW(plain.validate(), InputError);
    // Only the lamps the photo does not show: a change of the cells' targets, refused where
    // no cells are trained.
    plain.pretrainLampCellEpochs = 0;
    plain.lampCellsUnseenOnly = true;
    EXPECT_THROW(plain.validate(), InputError);
    plain.emitterCellWeight = 1.0;
    EXPECT_NO_THROW(plain.validate());
}

TEST_F(TrainerTest, EachPartOfTheNetworkStepsAtItsOwnRate) {
    // One Adam step moves no weight by more than about its learning rate (at most 1.001 times
    // it at the second step, whatever the gradients). With a pretrained classifier, the photo
    // encoder and classifier train at 10 times the rate, the rest of the emitter head at 100
    // times, and the rest of the network at the rate itself: each group's largest change over
    // the second step lies at or below its own rate and, for groups of many weights, well
    // above the rate of the group below.
    TrainOptions o = photoCellsOptions("lighthouse_trainer_rates");
    o.pretrainLampCellEpochs = 1;
    o.emitterCellWeight = 1.0;
    o.learningRate = 1e-4;
    o.iterations = 10;  // the rate drops tenfold only at iteration 8
    o.stopAfter = 1;
    o.averageDecay = 0.0;
    o.halfModel = false;
    std::ostringstream log;
    train(o, log);
    const LighthouseNet first = loadModel(o.out, torch::Device(torch::kCPU));
    train(o, log);  // resumes: the second step, with Adam's state restored
    ASSERT_NE(log.str().find("resuming"), std::string::npos) << log.str();
    const LighthouseNet second = loadModel(o.out, torch::Device(torch::kCPU));
    double trunk = 0, photo = 0, head = 0;
    const auto after = second->named_parameters();
    for (const auto& p : first->named_parameters()) {
        const double change = (p.value() - after[p.key()]).abs().max().item<double>();
        const std::string& name = p.key();
        double& group = name.rfind("emitter_head.photo_encoder.", 0) == 0 ||
                                name.rfind("emitter_head.photo_cells.", 0) == 0
                            ? photo
                        : name.rfind("emitter_head.", 0) == 0 ? head
                                                              : trunk;
        group = std::max(group, change);
    }
    const double lr = o.learningRate, margin = 1.01;
    EXPECT_LE(trunk, margin * lr);
    EXPECT_GT(trunk, 0.3 * lr);
    EXPECT_LE(photo, margin * 10 * lr);
    EXPECT_GT(photo, 3 * lr);
    EXPECT_LE(head, margin * 100 * lr);
    EXPECT_GT(head, 30 * lr);
    removeOutputs(o);
}

TEST_F(TrainerTest, TheViewHdrWeightSteersTraining) {
    // The tiny set's examples carry tgt.exr: with the HDR view loss on, the MPI's gradients
    // differ, so do the weights, and the log names the term; a negative weight is refused.
    ASSERT_TRUE(fs::is_regular_file(fs::path(dataDir()) / "000000" / "tgt.exr"));
    std::ostringstream log;
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_view_hdr", 0.0, 4.0,
                  [](TrainOptions& o, double w) { o.viewHdrWeight = w; }, log),
              1e-6)
        << "the HDR view weight changed nothing";
    EXPECT_NE(log.str().find("views also 4 x HDR"), std::string::npos) << log.str();
    TrainOptions negative = options("lighthouse_trainer_view_hdr_negative");
    negative.viewHdrWeight = -1.0;
    EXPECT_THROW(negative.validate(), InputError);
}

TEST_F(TrainerTest, TrainingUnderPruningSteersTrainingAndTheModelRecordsTheThreshold) {
    std::ostringstream log;
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_prune", 0.0, 0.3,
                  [](TrainOptions& o, double a) { o.pruneAlpha = a; }, log),
              1e-6)
        << "training under pruning changed nothing";
    EXPECT_NE(log.str().find("alpha below 0.3 pruned"), std::string::npos) << log.str();
    TrainOptions o = options("lighthouse_trainer_prune_record");
    o.iterations = 1;
    o.pruneAlpha = 0.3;
    train(o, log);
    EXPECT_DOUBLE_EQ(loadModel(o.out, torch::Device(torch::kCPU))->config.pruneAlpha, 0.3);
    removeOutputs(o);
    for (const double bad : {-0.1, 1.0}) {
        o.pruneAlpha = bad;
        EXPECT_THROW(o.validate(), InputError) << bad;
    }
}

TEST_F(TrainerTest, TrainingUnderAHighlightGainSteersTrainingAndTheModelRecordsIt) {
    // The tiny set's rooms have lamps, so its cubes go above white and the gain changes what
    // the losses see.
    std::ostringstream log;
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_gain", 1.0, 20.0,
                  [](TrainOptions& o, double k) { o.highlightGain = k; }, log),
              1e-6)
        << "training under a highlight gain changed nothing";
    EXPECT_NE(log.str().find("cubes under a highlight gain of 20"), std::string::npos) << log.str();
    TrainOptions o = options("lighthouse_trainer_gain_record");
    o.iterations = 1;
    o.highlightGain = 20.0;
    train(o, log);
    EXPECT_DOUBLE_EQ(loadModel(o.out, torch::Device(torch::kCPU))->config.highlightGain, 20.0);
    removeOutputs(o);
    for (const double bad : {0.5, 2000.0}) {
        o.highlightGain = bad;
        EXPECT_THROW(o.validate(), InputError) << bad;
    }
}

TEST_F(TrainerTest, TheBinaryAlphaPriorSteersTraining) {
    std::ostringstream log;
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_binary_alpha", 0.0, 50.0,
                  [](TrainOptions& o, double w) { o.alphaBinaryWeight = w; }, log),
              1e-6)
        << "the binary alpha prior changed nothing";
    EXPECT_NE(log.str().find("cubes also 50 x alpha (1 - alpha)"), std::string::npos) << log.str();
    TrainOptions negative = options("lighthouse_trainer_binary_alpha_negative");
    negative.alphaBinaryWeight = -1.0;
    EXPECT_THROW(negative.validate(), InputError);
}

TEST_F(TrainerTest, TheClosedRoomPriorSteersTraining) {
    std::ostringstream log;
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_closure", 0.0, 20.0,
                  [](TrainOptions& o, double w) { o.closureWeight = w; }, log),
              1e-6)
        << "the closed-room prior changed nothing";
    EXPECT_NE(log.str().find("20 x the transmittance left behind the volume"), std::string::npos)
        << log.str();
    TrainOptions bad = options("lighthouse_trainer_closure_bad");
    bad.closureWeight = -1.0;
    EXPECT_THROW(bad.validate(), InputError);
    bad.closureWeight = 101.0;
    EXPECT_THROW(bad.validate(), InputError);
}

TEST_F(TrainerTest, TheEnvmapSquaredErrorWeightSteersTraining) {
    // As the irradiance weight: off and strong give different weights, and the log says the
    // term is on; a negative weight and one above 100 are refused.
    std::ostringstream log;
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_squared", 0.0, 20.0,
                  [](TrainOptions& o, double w) { o.envmapSquaredWeight = w; }, log),
              1e-6)
        << "the squared-error weight changed nothing";
    EXPECT_NE(log.str().find("20 x squared sRGB"), std::string::npos) << log.str();
    TrainOptions negative = options("lighthouse_trainer_squared_negative");
    negative.envmapSquaredWeight = -1.0;
    EXPECT_THROW(negative.validate(), InputError);
    negative.envmapSquaredWeight = 101.0;
    EXPECT_THROW(negative.validate(), InputError);
}

TEST_F(TrainerTest, TheCoarseEnvmapWeightSteersTraining) {
    // As the irradiance weight: off and strong give different weights, and the log says the
    // term is on; a negative weight and one above 100 are refused.
    std::ostringstream log;
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_coarse", 0.0, 20.0,
                  [](TrainOptions& o, double w) { o.coarseEnvmapWeight = w; }, log),
              1e-6)
        << "the coarse envmap weight changed nothing";
    EXPECT_NE(log.str().find("20 x HDR over 4x4 blocks"), std::string::npos) << log.str();
    TrainOptions bad = options("lighthouse_trainer_coarse_bad");
    bad.coarseEnvmapWeight = -1.0;
    EXPECT_THROW(bad.validate(), InputError);
    bad.coarseEnvmapWeight = 101.0;
    EXPECT_THROW(bad.validate(), InputError);
    bad.coarseEnvmapWeight = 1.0;
    for (int block : {0, 61}) {
        bad.coarseEnvmapBlock = block;
        EXPECT_THROW(bad.validate(), InputError) << "block " << block;
    }
}

TEST_F(TrainerTest, TheCoarseEnvmapBlockSteersTraining) {
    // Blocks of 2 and of 8 pixels ask for different light, so the same steps give different
    // weights, and the log names the block in use.
    std::ostringstream log;
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_coarse_block", 2.0, 8.0,
                  [](TrainOptions& o, double block) {
                      o.coarseEnvmapWeight = 20.0;
                      o.coarseEnvmapBlock = int(block);
                  },
                  log),
              1e-6)
        << "the coarse envmap block changed nothing";
    EXPECT_NE(log.str().find("20 x HDR over 8x8 blocks"), std::string::npos) << log.str();
}

TEST_F(TrainerTest, TheHighlightWeightSteersTraining) {
    // The tiny set's rooms have lamps in their envmaps and masks beside them: off and strong
    // give different weights, and the log says the term is on.
    std::ostringstream log;
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_highlight", 0.0, 20.0,
                  [](TrainOptions& o, double w) { o.highlightWeight = w; }, log),
              1e-6)
        << "the highlight weight changed nothing";
    EXPECT_NE(log.str().find("20 x highlights"), std::string::npos) << log.str();
    TrainOptions negative = options("lighthouse_trainer_highlight_negative");
    negative.highlightWeight = -1.0;
    EXPECT_THROW(negative.validate(), InputError);
}

TEST_F(TrainerTest, MeteringForHighlightsChangesWhatTrainingSees) {
    // The tiny set's photos show lamps: letting none of the reference photo clip darkens the
    // examples (photos and targets alike), which changes the weights, and the log says so.
    std::ostringstream log;
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_metering", 1.0, 0.0,
                  [](TrainOptions& o, double f) { o.maxPhotoClipped = f; }, log),
              1e-6)
        << "metering for the highlights changed nothing";
    EXPECT_NE(log.str().find("photos exposed to clip on at most 0 of the reference view"),
              std::string::npos)
        << log.str();
    TrainOptions above = options("lighthouse_trainer_metering_above_one");
    above.maxPhotoClipped = 1.5;
    EXPECT_THROW(above.validate(), InputError);
}

TEST_F(TrainerTest, DirectSupervisionUsesTheOracleAndTheDepth) {
    std::ostringstream log;
    TrainOptions o = options("lighthouse_trainer_direct");
    o.iterations = 2;
    train(o, log);
    const std::string csv = readText(o.out + ".csv");
    ASSERT_NE(csv.find("loss_voxel"), std::string::npos);
    // Row 1: loss_voxel and loss_depth (columns 12 and 13) are positive.
    std::istringstream rows(csv);
    std::string header, row;
    std::getline(rows, header);
    std::getline(rows, row);
    std::vector<std::string> cells;
    std::istringstream fields(row);
    for (std::string f; std::getline(fields, f, ',');) cells.push_back(f);
    ASSERT_GE(cells.size(), 13u);
    EXPECT_GT(std::stod(cells[11]), 0.0) << row;
    EXPECT_GT(std::stod(cells[12]), 0.0) << row;
    removeOutputs(o);
}

TEST_F(TrainerTest, PaperModeTrainsWithoutThreeDimensionalGroundTruth) {
    std::ostringstream log;
    TrainOptions o = options("lighthouse_trainer_paper");
    o.supervision = "paper";
    o.iterations = 4;                      // stage 1 at 0, stage 2 from 1, stage 3 from 3
    o.configOverride->trainEnvWidth = 64;  // the PatchGAN discriminator needs at least 32 rows
    o.configOverride->trainEnvHeight = 32;
    train(o, log);
    EXPECT_TRUE(fs::is_regular_file(o.out));
    const std::string csv = readText(o.out + ".csv");
    std::istringstream rows(csv);
    std::string line;
    std::getline(rows, line);
    int lines = 0;
    while (std::getline(rows, line)) {
        if (line.empty()) continue;  // writeTextFile ends files with a newline of its own
        ++lines;
        std::vector<std::string> cells;
        std::istringstream fields(line);
        for (std::string f; std::getline(fields, f, ',');) cells.push_back(f);
        ASSERT_GE(cells.size(), 13u) << "line " << lines << ": '" << line << "'";
        EXPECT_EQ(std::stod(cells[11]), 0.0) << "no voxel loss without 3D ground truth: " << line;
        EXPECT_EQ(std::stod(cells[12]), 0.0) << "no depth loss without 3D ground truth: " << line;
        EXPECT_TRUE(std::isfinite(std::stod(cells[2]))) << line;
    }
    EXPECT_EQ(lines, 4);
    EXPECT_NE(csv.find("\n4,3,"), std::string::npos)
        << "the last iteration is in stage 3 (adversarial)";
    removeOutputs(o);
}

TEST_F(TrainerTest, TheDirectAdversarialWeightAddsThePatchGanFromTheFirstStep) {
    // Direct supervision with a PatchGAN weight: every iteration is in stage 3, with a
    // discriminator loss and a generator loss logged, and the weights differ from the run
    // without it. Without it, direct supervision stays in stage 2 with no adversarial loss.
    std::ostringstream log;
    const auto withEnvmapsForThePatchGan = [](TrainOptions& o) {
        o.configOverride->trainEnvWidth = 64;  // the discriminator needs at least 32 rows
        o.configOverride->trainEnvHeight = 32;
    };
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_direct_gan", 0.0, 1.0,
                  [&](TrainOptions& o, double w) {
                      withEnvmapsForThePatchGan(o);
                      o.directAdversarialWeight = w;
                  },
                  log),
              1e-6)
        << "the adversarial weight changed nothing";
    EXPECT_NE(log.str().find("1 x the PatchGAN generator loss"), std::string::npos) << log.str();
    EXPECT_NE(log.str().find(", discriminator "), std::string::npos)
        << "the progress lines show the adversarial losses: " << log.str();

    TrainOptions o = options("lighthouse_trainer_direct_gan_log");
    withEnvmapsForThePatchGan(o);
    o.iterations = 2;
    o.directAdversarialWeight = 0.5;
    train(o, log);
    std::istringstream rows(readText(o.out + ".csv"));
    std::string line;
    std::getline(rows, line);
    int lines = 0;
    while (std::getline(rows, line)) {
        if (line.empty()) continue;
        ++lines;
        std::vector<std::string> cells;
        std::istringstream fields(line);
        for (std::string f; std::getline(fields, f, ',');) cells.push_back(f);
        ASSERT_GE(cells.size(), 7u) << line;
        EXPECT_EQ(cells[1], "3") << "stage 3 from the first step: " << line;
        EXPECT_NE(std::stod(cells[5]), 0.0) << "a generator loss: " << line;
        EXPECT_GT(std::stod(cells[6]), 0.0) << "a discriminator loss: " << line;
    }
    EXPECT_EQ(lines, 2);
    removeOutputs(o);

    // What the discriminator sees changes what it asks for.
    EXPECT_GT(weightChangeOf(
                  "lighthouse_trainer_direct_gan_log", 0.0, 1.0,
                  [&](TrainOptions& o, double log) {
                      withEnvmapsForThePatchGan(o);
                      o.directAdversarialWeight = 1.0;
                      o.adversarialInput = log > 0 ? "log" : "srgb";
                  },
                  log),
              1e-6)
        << "the discriminator's input changed nothing";
    EXPECT_NE(log.str().find("the discriminator sees ln(1 + radiance)"), std::string::npos);

    TrainOptions bad = options("lighthouse_trainer_direct_gan_bad");
    bad.adversarialInput = "hdr";
    EXPECT_THROW(bad.validate(), InputError);
    bad.adversarialInput = "srgb";
    bad.directAdversarialWeight = -1.0;
    EXPECT_THROW(bad.validate(), InputError);
    bad.directAdversarialWeight = 0.5;
    bad.supervision = "paper";
    EXPECT_THROW(bad.validate(), InputError) << "the paper's supervision has its own stage";
}

TEST_F(TrainerTest, InitPartialStartsFromTheSharedParametersOfAnotherConfiguration) {
    // A model of twice the completion width shares only the MPI network with this one.
    TrainOptions source = options("lighthouse_trainer_partial_source");
    source.configOverride->baseWidth = 2 * source.configOverride->baseWidth;
    source.iterations = 1;
    source.halfModel = false;
    std::ostringstream log;
    train(source, log);

    TrainOptions o = options("lighthouse_trainer_partial");
    o.init = source.out;
    o.iterations = 1;
    o.learningRate = 1e-9;  // one step that moves no weight by more than about 1e-9
    EXPECT_THROW(train(o, log), InputError) << "another configuration needs --init-partial";
    o.initPartial = true;
    o.halfModel = false;
    o.averageDecay = 0.0;
    std::ostringstream partialLog;
    train(o, partialLog);
    EXPECT_NE(partialLog.str().find("that match in name and shape"), std::string::npos)
        << partialLog.str();
    const LighthouseNet wide = loadModel(source.out, torch::Device(torch::kCPU));
    const LighthouseNet started = loadModel(o.out, torch::Device(torch::kCPU));
    const auto wideParameters = wide->named_parameters();
    int shared = 0;
    for (const auto& p : started->named_parameters())
        if (p.key().rfind("mpi_net", 0) == 0) {
            ++shared;
            EXPECT_TRUE(torch::allclose(p.value(), wideParameters[p.key()], 0.0, 1e-6)) << p.key();
        }
    EXPECT_GT(shared, 0);
    removeOutputs(source);
    removeOutputs(o);
}

TEST_F(TrainerTest, InitPartialCarriesAModelIntoItsHeightProfileConfiguration) {
    TrainOptions source = options("lighthouse_trainer_profile_source");
    source.iterations = 1;
    source.halfModel = false;
    std::ostringstream log;
    train(source, log);

    TrainOptions o = options("lighthouse_trainer_profile");
    o.configOverride->heightProfile = true;
    o.init = source.out;
    o.initPartial = true;
    o.iterations = 1;
    o.halfModel = false;
    std::ostringstream profileLog;
    train(o, profileLog);
    const int levels = o.configOverride->levels;
    EXPECT_NE(profileLog.str().find("or only gained input channels (" + std::to_string(levels) +
                                    " stems"),
              std::string::npos)
        << profileLog.str();
    const LighthouseNet started = loadModel(o.out, torch::Device(torch::kCPU));
    EXPECT_TRUE(started->config.heightProfile);
    removeOutputs(source);
    removeOutputs(o);
}

TEST_F(TrainerTest, InitWidenStartsAWiderModelFromANarrowOne) {
    TrainOptions source = options("lighthouse_trainer_widen_source");
    source.iterations = 1;
    source.halfModel = false;
    std::ostringstream log;
    train(source, log);

    TrainOptions o = options("lighthouse_trainer_widen");
    o.configOverride->baseWidth = 2 * source.configOverride->baseWidth;
    o.init = source.out;
    o.initWiden = true;
    o.iterations = 1;
    o.learningRate = 1e-9;
    o.halfModel = false;
    o.averageDecay = 0.0;
    std::ostringstream widenLog;
    train(o, widenLog);
    EXPECT_NE(widenLog.str().find("widened"), std::string::npos) << widenLog.str();
    // The MPI network is copied; each completion weight reading a widened input is split in
    // two halves that sum to the narrow weight.
    const LighthouseNet narrow = loadModel(source.out, torch::Device(torch::kCPU));
    const LighthouseNet wide = loadModel(o.out, torch::Device(torch::kCPU));
    EXPECT_EQ(wide->config.baseWidth, 2 * narrow->config.baseWidth);
    const auto w = wide->completion[1]->down[0]->conv->weight;
    const auto n = narrow->completion[1]->down[0]->conv->weight;
    const int64_t half = w.size(1) / 2;
    EXPECT_TRUE(torch::allclose(
        (w.narrow(1, 0, half) + w.narrow(1, half, half)).narrow(0, 0, n.size(0)), n, 1e-4, 1e-6));
    removeOutputs(source);
    removeOutputs(o);
}

TEST_F(TrainerTest, UnknownSupervisionIsAClearError) {
    TrainOptions o = options("lighthouse_trainer_bad");
    o.supervision = "oracle";
    std::ostringstream log;
    EXPECT_THROW(train(o, log), InputError);
}

}  // namespace
}  // namespace lh::net
