// Photos are read upright: a JPEG whose EXIF Orientation says "rotate" comes out of readImage
// rotated. Known answer: a stored image of four coloured quadrants, and where each quadrant
// must land for every orientation.
#include "image/image_orientation.h"
#include "image/image_io.h"
#include "tests/support/exif_jpeg.h"

#include <gtest/gtest.h>

#include <array>
#include <string>

namespace lh {
namespace {

// Quadrant colours of the stored image: top-left, top-right, bottom-left, bottom-right.
constexpr std::array<std::array<unsigned char, 3>, 4> kQuadrant = {
    {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}}};

// A stored w x h image (multiples of 16, so that JPEG blocks do not straddle quadrants).
std::vector<unsigned char> quadrants(int w, int h) {
    std::vector<unsigned char> rgb(std::size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto& c = kQuadrant[(y >= h / 2 ? 2 : 0) + (x >= w / 2 ? 1 : 0)];
            for (int k = 0; k < 3; ++k) rgb[(std::size_t(y) * w + x) * 3 + k] = c[k];
        }
    return rgb;
}

// Which stored quadrant (index into kQuadrant) the upright pixel near (fx, fy) shows, the
// fractions of the upright width and height; -1 when the colour matches none.
int quadrantAt(const ImageRGB& image, double fx, double fy) {
    const float* p = image.at(int(fx * image.width), int(fy * image.height));
    for (int q = 0; q < 4; ++q) {
        bool match = true;
        for (int k = 0; k < 3; ++k)
            match = match && std::abs(p[k] - kQuadrant[q][k] / 255.0f) < 0.1f;
        if (match) return q;
    }
    return -1;
}

// The stored quadrants seen at the upright top-left, top-right, bottom-left, bottom-right.
std::array<int, 4> uprightQuadrants(const ImageRGB& image) {
    return {quadrantAt(image, 0.25, 0.25), quadrantAt(image, 0.75, 0.25),
            quadrantAt(image, 0.25, 0.75), quadrantAt(image, 0.75, 0.75)};
}

TEST(ImageOrientation, ReadImageTurnsEveryOrientationUpright) {
    const int w = 64, h = 32;
    // TL=0, TR=1, BL=2, BR=3 stored; what the upright corners show, per orientation 1..8.
    const std::array<std::array<int, 4>, 8> expected = {{
        {0, 1, 2, 3},  // 1 as stored
        {1, 0, 3, 2},  // 2 mirrored left-right
        {3, 2, 1, 0},  // 3 rotated 180
        {2, 3, 0, 1},  // 4 mirrored top-bottom
        {0, 2, 1, 3},  // 5 transposed
        {2, 0, 3, 1},  // 6 rotated 90 clockwise
        {3, 1, 2, 0},  // 7 transverse
        {1, 3, 0, 2},  // 8 rotated 90 counter-clockwise
    }};
    for (int orientation = 1; orientation <= 8; ++orientation) {
        test::ExifTags tags;
        tags.orientation = orientation;
        const std::string path = test::makeJpeg("orient" + std::to_string(orientation) + ".jpg", w,
                                                h, tags, quadrants(w, h));
        EXPECT_EQ(exifOrientation(path), orientation);
        const ImageRGB image = readImage(path);
        const bool swapped = orientation >= 5;
        EXPECT_EQ(image.width, swapped ? h : w) << "orientation " << orientation;
        EXPECT_EQ(image.height, swapped ? w : h) << "orientation " << orientation;
        EXPECT_EQ(uprightQuadrants(image), expected[orientation - 1])
            << "orientation " << orientation;
    }
}

TEST(ImageOrientation, APhotoWithoutExifIsReadAsStored) {
    const std::string path = test::makeJpeg("no_exif.jpg", 32, 16, std::nullopt, quadrants(32, 16));
    EXPECT_EQ(exifOrientation(path), 1);
    const ImageRGB image = readImage(path);
    EXPECT_EQ(image.width, 32);
    EXPECT_EQ(image.height, 16);
    EXPECT_EQ(uprightQuadrants(image), (std::array<int, 4>{0, 1, 2, 3}));
}

TEST(ImageOrientation, RotationKeepsEveryPixelExactly) {
    ImageRGB stored(3, 2);
    for (std::size_t i = 0; i < stored.pixels.size(); ++i) stored.pixels[i] = float(i);
    const ImageRGB cw = applyOrientation(stored, 6);
    ASSERT_EQ(cw.width, 2);
    ASSERT_EQ(cw.height, 3);
    // Rotated 90 degrees clockwise, the stored bottom-left pixel is the upright top-left.
    EXPECT_EQ(cw.at(0, 0)[0], stored.at(0, 1)[0]);
    EXPECT_EQ(cw.at(1, 0)[0], stored.at(0, 0)[0]);
    EXPECT_EQ(cw.at(0, 2)[0], stored.at(2, 1)[0]);
    // 8 undoes 6; 3 twice is the identity.
    EXPECT_EQ(applyOrientation(cw, 8).pixels, stored.pixels);
    EXPECT_EQ(applyOrientation(applyOrientation(stored, 3), 3).pixels, stored.pixels);
    EXPECT_EQ(applyOrientation(stored, 9).pixels, stored.pixels);  // out of range: as stored
}

}  // namespace
}  // namespace lh
