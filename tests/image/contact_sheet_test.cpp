// contactSheet with known answers.
#include "image/contact_sheet.h"

#include "core/errors.h"

#include <gtest/gtest.h>

namespace lh {
namespace {

ImageRGB filled(int w, int h, float r, float g, float b) {
    ImageRGB image(w, h);
    for (int i = 0; i < w * h; ++i) {
        image.pixels[3 * i] = r;
        image.pixels[3 * i + 1] = g;
        image.pixels[3 * i + 2] = b;
    }
    return image;
}

TEST(ContactSheet, TilesKeepTheirAspectInsideADarkBorder) {
    // Row 1: a red 8x4 (scaled to 4x2) and a green 2x2; row 2: a blue 4x4 (scaled to 2x2).
    const ImageRGB sheet =
        contactSheet({{filled(8, 4, 1, 0, 0), filled(2, 2, 0, 1, 0)}, {filled(4, 4, 0, 0, 1)}},
                     /*tileHeight=*/2, /*gap=*/1);
    // Width: gap + (4 + gap) + (2 + gap) = 9; height: gap + 2 rows x (2 + gap) = 7.
    ASSERT_EQ(sheet.width, 9);
    ASSERT_EQ(sheet.height, 7);
    const auto colour = [&](int x, int y) {
        const float* p = sheet.at(x, y);
        return std::vector<float>{p[0], p[1], p[2]};
    };
    const std::vector<float> border{0.02f, 0.02f, 0.02f}, red{1, 0, 0}, green{0, 1, 0},
        blue{0, 0, 1};
    EXPECT_EQ(colour(0, 0), border);
    EXPECT_EQ(colour(1, 1), red);
    EXPECT_EQ(colour(4, 2), red);
    EXPECT_EQ(colour(5, 1), border);  // the gap between the tiles
    EXPECT_EQ(colour(6, 1), green);
    EXPECT_EQ(colour(7, 2), green);
    EXPECT_EQ(colour(1, 4), blue);
    EXPECT_EQ(colour(2, 5), blue);
    EXPECT_EQ(colour(3, 4), border);  // row 2 is narrower: the rest is border
    EXPECT_EQ(colour(8, 6), border);
    EXPECT_THROW(contactSheet({}, 2), InputError);
    EXPECT_THROW(contactSheet({{filled(2, 2, 1, 1, 1)}}, 0), InputError);
}

}  // namespace
}  // namespace lh
