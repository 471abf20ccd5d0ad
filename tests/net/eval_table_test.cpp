// Table 2's second table, on what each method invents: the unobserved pixels' PSNR, their
// display bias and their PSNR without it, from scores with a known answer.
#include "net/eval_table.h"

#include "net/evaluation.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lh::net {
namespace {

TEST(EvalTable, InventedPartsAreScoredWithAndWithoutTheirBias) {
    // Two envmaps whose unobserved pixels have a mean square difference of 0.01 (20 dB), one
    // 0.05 too bright and one 0.05 too dark: without the bias 10 log10(1 / 0.0075) = 21.25 dB.
    MethodScores ours;
    ours.name = "ours";
    for (double bias : {0.05, -0.05}) {
        MetricValues v{};
        v[8] = 20.0;  // psnr_unobserved_db
        v[9] = bias;  // srgb_bias_unobserved
        addScores(ours, v);
    }
    const std::string md = evalTableMarkdown({ours}, 2, "data", "wide");
    EXPECT_NE(md.find("| PSNR unobserved (dB) | display bias unobserved | PSNR unobserved "
                      "without the bias (dB) |"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| ours | 20.00 +- 0.00 | +0.000 +- "), std::string::npos) << md;
    EXPECT_NE(md.find(" | 21.25 +- 0.00 |\n"), std::string::npos) << md;
}

}  // namespace
}  // namespace lh::net
