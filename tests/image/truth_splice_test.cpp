#include "image/truth_splice.h"

#include "core/errors.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace lh {
namespace {

// A 4x1 prediction of grey 0.1 against a truth whose pixels are 0.5, 2 (a window), 3 (a lamp)
// and 0.2; the first two pixels are observed.
struct Case {
    ImageRGB prediction{4, 1}, truth{4, 1};
    std::vector<std::uint8_t> observed{1, 1, 0, 0};
    Case() {
        const float values[4] = {0.5f, 2.0f, 3.0f, 0.2f};
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) {
                prediction.at(x, 0)[c] = 0.1f;
                truth.at(x, 0)[c] = values[x];
            }
    }
    // The red channel of each pixel of `image`.
    static std::vector<float> reds(const ImageRGB& image) {
        std::vector<float> out;
        for (int x = 0; x < image.width; ++x) out.push_back(image.at(x, 0)[0]);
        return out;
    }
};

TEST(TruthSplice, EachPartTakesItsPixelsFromTheTruthAndKeepsTheRest) {
    const Case k;
    EXPECT_EQ(Case::reds(spliceTruth(k.prediction, k.truth, TruthPart::Observed, k.observed)),
              (std::vector<float>{0.5f, 2.0f, 0.1f, 0.1f}));
    EXPECT_EQ(Case::reds(spliceTruth(k.prediction, k.truth, TruthPart::Unobserved, k.observed)),
              (std::vector<float>{0.1f, 0.1f, 3.0f, 0.2f}));
    EXPECT_EQ(
        Case::reds(spliceTruth(k.prediction, k.truth, TruthPart::LampsAndWindows, k.observed)),
        (std::vector<float>{0.1f, 2.0f, 3.0f, 0.1f}))
        << "only the pixels whose true luminance is above 1";
    EXPECT_EQ(Case::reds(spliceTruth(k.prediction, k.truth, TruthPart::ObservedLampsAndWindows,
                                     k.observed)),
              (std::vector<float>{0.1f, 2.0f, 0.1f, 0.1f}))
        << "only the observed pixel whose true luminance is above 1";
    EXPECT_EQ(Case::reds(spliceTruth(k.prediction, k.truth, TruthPart::UnobservedLampsAndWindows,
                                     k.observed)),
              (std::vector<float>{0.1f, 0.1f, 3.0f, 0.1f}))
        << "only the unobserved pixel whose true luminance is above 1";
}

// A 12x1 envmap, 30 degrees a column: an observed window at column 0, unobserved lamps at
// columns 2 and 11 (the last column, to see the turn wrap around).
TEST(TruthSplice, TurnedPartsMoveTheUnseenLampsSidewaysAndLeaveTheirPlaceAsPredicted) {
    ImageRGB prediction(12, 1), truth(12, 1);
    std::vector<std::uint8_t> observed(12, 0);
    observed[0] = 1;
    for (int x = 0; x < 12; ++x)
        for (int c = 0; c < 3; ++c) {
            prediction.at(x, 0)[c] = 0.1f;
            truth.at(x, 0)[c] = x == 0 ? 2.0f : x == 2 ? 3.0f : x == 11 ? 5.0f : 0.4f;
        }
    std::vector<float> turned30(12, 0.1f), turned60(12, 0.1f);
    turned30[3] = 3.0f;  // column 2 + 1
    turned30[0] = 5.0f;  // column 11 + 1, wrapped
    turned60[4] = 3.0f;
    turned60[1] = 5.0f;
    EXPECT_DOUBLE_EQ(truthPartTurnDegrees(TruthPart::UnobservedLampsAndWindowsTurned30), 30.0);
    EXPECT_DOUBLE_EQ(truthPartTurnDegrees(TruthPart::UnobservedLampsAndWindows), 0.0);
    EXPECT_EQ(Case::reds(spliceTruth(prediction, truth,
                                     TruthPart::UnobservedLampsAndWindowsTurned30, observed)),
              turned30)
        << "the observed window stays out, and columns 2 and 11 keep the prediction";
    EXPECT_EQ(Case::reds(spliceTruth(prediction, truth,
                                     TruthPart::UnobservedLampsAndWindowsTurned60, observed)),
              turned60);
}

TEST(TruthSplice, MismatchedSizesAreAClearError) {
    const Case k;
    EXPECT_THROW(spliceTruth(ImageRGB(2, 1), k.truth, TruthPart::Observed, k.observed), InputError);
    EXPECT_THROW(spliceTruth(k.prediction, k.truth, TruthPart::Observed, {1, 0}), InputError);
}

TEST(TruthSplice, EveryPartHasItsOwnName) {
    EXPECT_STRNE(truthPartName(TruthPart::Observed), truthPartName(TruthPart::Unobserved));
    EXPECT_STRNE(truthPartName(TruthPart::Unobserved), truthPartName(TruthPart::LampsAndWindows));
    EXPECT_STRNE(truthPartName(TruthPart::LampsAndWindows),
                 truthPartName(TruthPart::ObservedLampsAndWindows));
    EXPECT_STRNE(truthPartName(TruthPart::ObservedLampsAndWindows),
                 truthPartName(TruthPart::UnobservedLampsAndWindows));
    EXPECT_STRNE(truthPartName(TruthPart::UnobservedLampsAndWindows),
                 truthPartName(TruthPart::UnobservedLampsAndWindowsTurned30));
    EXPECT_STRNE(truthPartName(TruthPart::UnobservedLampsAndWindowsTurned30),
                 truthPartName(TruthPart::UnobservedLampsAndWindowsTurned60));
}

}  // namespace
}  // namespace lh
