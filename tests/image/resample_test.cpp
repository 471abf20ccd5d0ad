// resizeImage with known answers.
#include "image/resample.h"

#include "core/errors.h"

#include <gtest/gtest.h>

namespace lh {
namespace {

// A w x h image whose red channel is `values` (row-major), green 2x red, blue 0.
ImageRGB imageOf(int w, int h, const std::vector<float>& values) {
    ImageRGB image(w, h);
    for (int i = 0; i < w * h; ++i) {
        image.pixels[3 * i] = values[i];
        image.pixels[3 * i + 1] = 2 * values[i];
    }
    return image;
}

TEST(ResizeImage, HalvingAveragesEachTwoByTwoBlock) {
    const ImageRGB image = imageOf(4, 2,
                                   {1, 3, 10, 20,  //
                                    5, 7, 30, 40});
    const ImageRGB half = resizeImage(image, 2, 1);
    ASSERT_EQ(half.width, 2);
    ASSERT_EQ(half.height, 1);
    EXPECT_FLOAT_EQ(half.at(0, 0)[0], 4.f);   // (1 + 3 + 5 + 7) / 4
    EXPECT_FLOAT_EQ(half.at(1, 0)[0], 25.f);  // (10 + 20 + 30 + 40) / 4
    EXPECT_FLOAT_EQ(half.at(1, 0)[1], 50.f);  // every channel alike
    EXPECT_FLOAT_EQ(half.at(1, 0)[2], 0.f);
}

TEST(ResizeImage, ANonIntegerRatioWeightsPartialPixelsByOverlap) {
    // 3 -> 2 pixels: target pixel 0 covers source [0, 1.5): (a + b / 2) / 1.5.
    const ImageRGB out = resizeImage(imageOf(3, 1, {3, 6, 9}), 2, 1);
    EXPECT_FLOAT_EQ(out.at(0, 0)[0], (3.f + 0.5f * 6.f) / 1.5f);
    EXPECT_FLOAT_EQ(out.at(1, 0)[0], (0.5f * 6.f + 9.f) / 1.5f);
    // The mean over the image is kept.
    EXPECT_FLOAT_EQ((out.at(0, 0)[0] + out.at(1, 0)[0]) / 2, 6.f);
}

TEST(ResizeImage, GrowingRepeatsPixelsAndTheSameSizeIsTheIdentity) {
    const ImageRGB image = imageOf(2, 1, {1, 5});
    const ImageRGB grown = resizeImage(image, 4, 2);
    for (int y = 0; y < 2; ++y) {
        EXPECT_FLOAT_EQ(grown.at(0, y)[0], 1.f);
        EXPECT_FLOAT_EQ(grown.at(1, y)[0], 1.f);
        EXPECT_FLOAT_EQ(grown.at(2, y)[0], 5.f);
        EXPECT_FLOAT_EQ(grown.at(3, y)[0], 5.f);
    }
    EXPECT_EQ(resizeImage(image, 2, 1).pixels, image.pixels);
}

TEST(ResizeImage, EmptyImagesAndSizesAreRefused) {
    EXPECT_THROW(resizeImage(ImageRGB(), 2, 2), InputError);
    EXPECT_THROW(resizeImage(imageOf(1, 1, {1}), 0, 2), InputError);
    EXPECT_THROW(resizeImage(imageOf(1, 1, {1}), 2, -1), InputError);
}

}  // namespace
}  // namespace lh
