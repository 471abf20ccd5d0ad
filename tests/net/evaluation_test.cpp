// `lighthouse eval`'s headroom rows on a tiny data set and an untrained model: each row is
// ours with one part of the truth put in, so the part put in scores perfectly and the rest
// scores as ours. And --shell, which changes ours and nothing else; and the notes that say how
// ours was predicted; and where an emitter model's lamps are, seen from each envmap's point.
#include "net/evaluation.h"
#include "core/errors.h"
#include "net/eval_table.h"
#include "net/lighthouse_net.h"
#include "tests/net/tiny_training_set.h"

#include "tests/support/temp_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace lh::net {
namespace {

namespace fs = std::filesystem;

// A tiny data set, an untrained model of `config` (weights from `seed`) and eval's options for
// them: no oracle, one thread. The files go when it does.
struct UntrainedEval {
    std::string data, model, out;
    EvalOptions options;
    UntrainedEval(const std::string& name, const NetConfig& config, int seed)
        : data(test::uniqueTempPath(name + "_data")),
          model(test::uniqueTempPath(name + ".pt")),
          out(test::uniqueTempPath(name + "_out")) {
        test::writeTinyTrainingSet(data);
        torch::manual_seed(seed);
        LighthouseNet untrained(config);
        saveModel(untrained, model);
        options.data = data;
        options.model = model;
        options.out = out;
        options.oracle = false;
        options.threads = 1;
    }
    ~UntrainedEval() {
        fs::remove_all(data);
        fs::remove(model);
        fs::remove_all(out);
    }
};

TEST(Evaluation, HeadroomRowsPutOnePartOfTheTruthIntoOurs) {
    UntrainedEval run("lighthouse_eval_test", test::tinyHdrConfig(), 7);
    EvalOptions& o = run.options;
    const std::string& out = run.out;
    o.headroom = true;
    std::ostringstream progress;
    const EvalReport report = evaluate(o, progress);

    ASSERT_EQ(report.headroom.size(), 7u);
    EXPECT_TRUE(report.lamps.empty()) << "a model without an emitter head has no lamps";
    EXPECT_FALSE(fs::exists(fs::path(out) / "lamps.csv"));
    const MethodScores& ours = report.methods[0];
    const MethodScores &observed = report.headroom[0], &unobserved = report.headroom[1];
    ASSERT_EQ(observed.psnrAll.size(), ours.psnrAll.size());
    int withBothParts = 0;
    for (size_t i = 0; i < ours.psnrAll.size(); ++i) {
        if (std::isnan(ours.psnrObserved[i]) || std::isnan(ours.psnrUnobserved[i])) continue;
        ++withBothParts;
        EXPECT_EQ(observed.psnrObserved[i], INFINITY) << "the true observed pixels are perfect";
        EXPECT_EQ(observed.psnrUnobserved[i], ours.psnrUnobserved[i]) << "the rest is ours";
        EXPECT_EQ(unobserved.psnrUnobserved[i], INFINITY);
        EXPECT_EQ(unobserved.psnrObserved[i], ours.psnrObserved[i]);
        EXPECT_GT(observed.psnrAll[i], ours.psnrAll[i]);
    }
    EXPECT_GT(withBothParts, 0) << "no envmap with observed and unobserved pixels to test on";
    EXPECT_NE(report.markdown.find("| ours + true lamps and windows"), std::string::npos)
        << report.markdown;
    // With the true lamps and windows put in, every true highlight shows where it is.
    const MethodScores& lamps = report.headroom[2];
    int withHighlights = 0;
    for (size_t i = 0; i < lamps.highlightRecall.size(); ++i) {
        if (std::isnan(lamps.highlightRecall[i])) continue;
        ++withHighlights;
        EXPECT_EQ(lamps.highlightRecall[i], 1.0);
    }
    EXPECT_GT(withHighlights, 0) << "no envmap with a lamp or window to test on";
    // The unobserved lamps and windows change only unobserved pixels.
    const MethodScores& unseenLamps = report.headroom[4];
    for (size_t i = 0; i < ours.psnrObserved.size(); ++i) {
        if (!std::isnan(ours.psnrObserved[i])) {
            EXPECT_EQ(unseenLamps.psnrObserved[i], ours.psnrObserved[i]);
        }
    }
    EXPECT_NE(report.markdown.find("| ours + true unobserved lamps and windows |"),
              std::string::npos)
        << report.markdown;
    EXPECT_NE(report.markdown.find("turned: put in that many degrees to the side"),
              std::string::npos)
        << report.markdown;
    EXPECT_NE(report.markdown.find("| ours + true unobserved lamps and windows, turned 60 deg |"),
              std::string::npos)
        << report.markdown;
    EXPECT_NE(report.markdown.find("| method | highlight recall | highlight precision |"),
              std::string::npos)
        << report.markdown;

    // --shell scores the shelled volumes and says so; the MPI-only row does not change.
    EvalOptions shelled = o;
    shelled.headroom = false;
    shelled.shell = true;
    const EvalReport withShell = evaluate(shelled, progress);
    EXPECT_NE(withShell.markdown.find("collapsed into an opaque shell"), std::string::npos);
    EXPECT_EQ(report.markdown.find("collapsed into an opaque shell"), std::string::npos);
    ASSERT_EQ(withShell.methods.size(), report.methods.size());
    EXPECT_EQ(withShell.methods[1].psnrAll, report.methods[1].psnrAll);
    EXPECT_NE(withShell.methods[0].psnrAll, ours.psnrAll);

    o.shard = Shard{0, 2, true};
    EXPECT_THROW(evaluate(o, progress), InputError) << "headroom rows are not sharded";
}

TEST(Evaluation, AnEmitterModelsLampsAreScoredFromEveryEnvmapsPoint) {
    NetConfig config = test::tinyHdrConfig();
    config.emitters = 2;
    UntrainedEval run("lighthouse_eval_lamps", config, 8);
    std::ostringstream progress;
    const EvalReport report = evaluate(run.options, progress);
    const std::size_t envmaps = report.methods[0].psnrAll.size();
    ASSERT_EQ(report.lamps.size(), 2 * envmaps);  // each lamp from each envmap's point
    int scored = 0;
    for (const LampPlacement& lamp : report.lamps) {
        EXPECT_LT(lamp.lamp, 2u);
        EXPECT_GT(lamp.alpha, 0.0);
        if (std::isnan(lamp.degrees)) continue;
        ++scored;
        EXPECT_GE(lamp.degrees, 0.0);
        EXPECT_LE(lamp.degrees, 180.0);
    }
    EXPECT_GT(scored, 0) << "no envmap with a lamp or window to place against";
    EXPECT_NE(report.markdown.find("Lamps of the emitter head (lamps.csv)"), std::string::npos)
        << report.markdown;
    EXPECT_TRUE(fs::is_regular_file(fs::path(run.out) / "lamps.csv"));
}

TEST(Evaluation, UnclippedPhotosReachTheModelAndAreRequiredWhereAsked) {
    NetConfig config = test::tinyHdrConfig();
    config.width = 64;
    config.height = 32;
    config.emitters = 3;
    config.emitterPhoto = config.emitterPhotoUnclipped = true;
    UntrainedEval run("lighthouse_eval_unclipped", config, 9);
    std::ostringstream progress;
    run.options.out = run.out + "_png";
    const EvalReport png = evaluate(run.options, progress);
    run.options.out = run.out;
    run.options.unclippedPhotos = true;
    const EvalReport exr = evaluate(run.options, progress);
    ASSERT_EQ(png.methods.size(), exr.methods.size());
    ASSERT_EQ(png.methods[0].name, "ours");
    // The renders are not the 8-bit photos (and the rooms' lamps are brighter than 1 in them).
    EXPECT_NE(png.methods[0].psnrAll, exr.methods[0].psnrAll);
    EXPECT_NE(exr.markdown.find("`--unclipped-photos`"), std::string::npos) << exr.markdown;
    EXPECT_EQ(png.markdown.find("`--unclipped-photos`"), std::string::npos);
    fs::remove_all(run.out + "_png");
    // The target view's render is not read: without it the scores are the same.
    fs::remove(fs::path(run.data) / "000001" / "tgt.exr");
    fs::remove_all(run.out);
    EXPECT_EQ(evaluate(run.options, progress).methods[0].psnrAll, exr.methods[0].psnrAll);
    // An example without its source render: one error that names the option, before any
    // output is written.
    fs::remove(fs::path(run.data) / "000001" / "src.exr");
    fs::remove_all(run.out);
    try {
        evaluate(run.options, progress);
        FAIL() << "an example without src.exr was scored";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("--unclipped-photos"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("src.exr"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(run.out));
}

TEST(Evaluation, AFailedEvalLeavesNoFolderItMade) {
    UntrainedEval run("lighthouse_eval_fails", test::tinyHdrConfig(), 10);
    std::ofstream(fs::path(run.data) / "000002" / "ref.png") << "not a photo";
    std::ostringstream progress;
    EXPECT_THROW(evaluate(run.options, progress), FileError);
    EXPECT_FALSE(fs::exists(run.out)) << "the failed eval left its output folder";
    // A folder the user made stays.
    fs::create_directories(run.out);
    EXPECT_THROW(evaluate(run.options, progress), FileError);
    EXPECT_TRUE(fs::is_directory(run.out));
}

TEST(Evaluation, TheNotesSayHowOursWasPredicted) {
    EXPECT_EQ(evalPredictionNotes(1.0, 1.0, false), "");
    EXPECT_NE(
        evalPredictionNotes(10.0, 1.0, false).find("above white, times 10 (`--highlight-gain`)"),
        std::string::npos);
    EXPECT_NE(evalPredictionNotes(30.0, 1.25, false)
                  .find("above luminance 1.25, times 30 (`--highlight-gain`, `--highlight-knee`)"),
              std::string::npos);
    // A knee without a gain changes nothing, so it is not noted.
    EXPECT_EQ(evalPredictionNotes(1.0, 1.25, false), "");
    EXPECT_NE(evalPredictionNotes(1.0, 1.0, true).find("`--no-shell` scores the fog"),
              std::string::npos);
    EXPECT_NE(evalPredictionNotes(1.0, 1.0, false, true).find("`--unclipped-photos`"),
              std::string::npos);
}

}  // namespace
}  // namespace lh::net
