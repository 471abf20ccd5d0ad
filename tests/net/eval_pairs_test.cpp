// `lighthouse eval-diff`: metrics.csv read back as eval writes it, and the paired difference of
// two evals with a known mean and standard error, pairs matched by example and envmap, NaN
// pairs left out, and the errors for files that are no eval's and evals that share nothing.
#include "net/eval_pairs.h"

#include "core/errors.h"
#include "tests/support/temp_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace lh::net {
namespace {

namespace fs = std::filesystem;

// A row of `method` whose PSNR (column 0) and angular error (column 1) are given, the rest 0.
EvalCsvRow row(const std::string& example, std::size_t envmap, double psnr, double angle,
               const std::string& method = "ours") {
    EvalCsvRow r;
    r.example = example;
    r.envmap = envmap;
    r.method = method;
    r.values.fill(0.0);
    r.values[0] = psnr;
    r.values[1] = angle;
    return r;
}

TEST(EvalCsv, ReadsBackWhatEvalWrites) {
    const std::string path = test::uniqueTempPath("lighthouse_eval_csv") + ".csv";
    MetricValues values;
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.5 + double(i);
    values[11] = std::nan("");  // an envmap without highlights has no precision
    {
        std::ofstream out(path);
        out << evalCsvHeader() << evalCsvRow("07", 2, "ours, MPI only", values, false);
    }
    const auto rows = readEvalCsv(path);
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_EQ(rows[0].example, "07");
    EXPECT_EQ(rows[0].envmap, 2u);
    EXPECT_EQ(rows[0].method, "ours, MPI only");
    EXPECT_DOUBLE_EQ(rows[0].values[6], 6.5);
    EXPECT_TRUE(std::isnan(rows[0].values[11]));
    {
        std::ofstream out(path);
        out << "example,envmap,method,psnr\n07,2,\"ours\",1\n";
    }
    EXPECT_THROW(readEvalCsv(path), FileError);  // another header
    {
        std::ofstream out(path);
        out << evalCsvHeader() << "07,2,\"ours\",1,2\n";
    }
    EXPECT_THROW(readEvalCsv(path), FileError);  // a short row
    fs::remove(path);
    EXPECT_THROW(readEvalCsv(path), FileError);  // gone
}

TEST(PairedDifferences, MeanAndStandardErrorOfThePairs) {
    // PSNR 10, 12, 14 against 11, 12.5, 16: differences 1, 0.5, 2, mean 7/6, sample variance
    // 7/12, standard error sqrt(7/36) = 0.4410. B's extra envmap and the baseline's rows are
    // not paired; A's angle of envmap 1 is NaN, so the angle has two pairs: +3 and +5.
    const std::vector<EvalCsvRow> a = {row("00", 0, 10, 8), row("00", 1, 12, std::nan("")),
                                       row("01", 0, 14, 9), row("00", 0, 1, 1, "baseline")};
    const std::vector<EvalCsvRow> b = {row("01", 0, 16, 14), row("00", 0, 11, 11),
                                       row("00", 1, 12.5, 2), row("02", 0, 40, 0),
                                       row("00", 0, 50, 50, "baseline")};
    const auto d = pairedDifferences(a, b, "ours");
    ASSERT_EQ(d.size(), std::size_t(kEnvmapMetricColumns));
    EXPECT_EQ(d[0].metric, "psnr_all_db");
    EXPECT_EQ(d[0].pairs, 3);
    EXPECT_NEAR(d[0].mean, 7.0 / 6.0, 1e-12);
    EXPECT_NEAR(d[0].standardError, std::sqrt(7.0 / 36.0), 1e-12);
    EXPECT_EQ(d[0].better, 1);
    EXPECT_EQ(d[1].pairs, 2);
    EXPECT_NEAR(d[1].mean, 4.0, 1e-12);
    EXPECT_NEAR(d[1].standardError, 1.0, 1e-12);
    EXPECT_EQ(d[1].better, -1);
    EXPECT_EQ(d[7].metric, "radiance_ratio");
    EXPECT_EQ(d[7].better, 0);
    // PSNR up by 2.6 standard errors: B better; the angle up by 4: B worse; the rest 0.
    const std::string table = pairedDifferencesMarkdown(d, "a.csv", "b.csv", "ours");
    EXPECT_NE(table.find("| psnr_all_db | 3 | +1.1667 | 0.4410 | B better |"), std::string::npos)
        << table;
    EXPECT_NE(table.find("| angular_all_deg | 2 | +4.0000 | 1.0000 | B worse |"), std::string::npos)
        << table;
    // An eval against itself: no difference anywhere, and no metric read as better or worse.
    const std::string same =
        pairedDifferencesMarkdown(pairedDifferences(a, a, "ours"), "a", "a", "ours");
    EXPECT_NE(same.find("| psnr_all_db | 3 | +0.0000 | 0.0000 | the same on every envmap |"),
              std::string::npos)
        << same;
    EXPECT_EQ(same.find("B worse"), std::string::npos) << same;
    EXPECT_EQ(same.find("B better"), std::string::npos) << same;
    // The same evals the other way round: the differences change sign.
    EXPECT_NEAR(pairedDifferences(b, a, "ours")[0].mean, -7.0 / 6.0, 1e-12);
    // The baseline's one pair has a mean but no standard error.
    const auto baseline = pairedDifferences(a, b, "baseline");
    EXPECT_EQ(baseline[0].pairs, 1);
    EXPECT_DOUBLE_EQ(baseline[0].mean, 49.0);
    EXPECT_TRUE(std::isnan(baseline[0].standardError));
}

TEST(PairedDifferences, RefusesEvalsWithNothingInCommonOrTwiceTheSameEnvmap) {
    const std::vector<EvalCsvRow> a = {row("00", 0, 10, 8)};
    EXPECT_THROW(pairedDifferences(a, {row("01", 0, 10, 8)}, "ours"), InputError);
    EXPECT_THROW(pairedDifferences(a, a, "oracle"), InputError);
    EXPECT_THROW(pairedDifferences(a, {row("00", 0, 10, 8), row("00", 0, 11, 8)}, "ours"),
                 InputError);
}

}  // namespace
}  // namespace lh::net
