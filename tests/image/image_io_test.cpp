#include "image/image_io.h"

#include "core/errors.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// A fresh directory per test, removed afterwards.
struct ScratchDir {
    fs::path path;
    explicit ScratchDir(const std::string& name)
        : path(fs::temp_directory_path() /
               ("lh_image_io_" + std::to_string(::getpid()) + "_" + name)) {
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~ScratchDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    std::string file(const std::string& name) const { return (path / name).string(); }
};

std::vector<std::string> listDir(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::uint32_t bitsOf(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return bits;
}

void writeBytes(const std::string& path, const std::vector<char>& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

std::vector<char> randomBytes(std::size_t count) {
    std::mt19937 rng(1234);  // fixed seed: the same "corrupt" file every run
    std::vector<char> bytes(count);
    for (char& b : bytes) b = static_cast<char>(rng() & 0xff);
    return bytes;
}

// A small image whose values cover ordinary, HDR, tiny, negative and zero radiance.
lh::ImageRGB sampleImage() {
    lh::ImageRGB image(7, 5);
    const float special[] = {
        1e6f, 1e-8f,      0.0f, -3.5f, 1e-40f /* denormal */, std::numeric_limits<float>::max(),
        0.1f, 1.0f / 3.0f};
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = i < std::size(special) ? special[i] : 0.013f * float(i);
    return image;
}

}  // namespace

TEST(ImageIo, SrgbRoundTripsOverUnitInterval) {
    for (int i = 0; i <= 100000; ++i) {
        const float x = float(i) / 100000.0f;
        EXPECT_NEAR(lh::srgbDecode(lh::srgbEncode(x)), x, 1e-6f) << "x = " << x;
        EXPECT_NEAR(lh::srgbEncode(lh::srgbDecode(x)), x, 1e-6f) << "x = " << x;
    }
}

TEST(ImageIo, SrgbKnownValues) {
    EXPECT_EQ(lh::srgbEncode(0.0f), 0.0f);
    EXPECT_EQ(lh::srgbEncode(1.0f), 1.0f);
    EXPECT_EQ(lh::srgbDecode(1.0f), 1.0f);
    EXPECT_NEAR(lh::srgbEncode(0.0031308f), 0.04045f, 1e-6f);  // the branch point
    EXPECT_NEAR(lh::srgbDecode(0.04045f), 0.0031308f, 1e-7f);
    EXPECT_NEAR(lh::srgbEncode(0.5f), 0.735357f, 1e-6f);
    EXPECT_NEAR(lh::srgbDecode(0.735357f), 0.5f, 1e-6f);
    EXPECT_NEAR(lh::srgbEncode(0.001f), 0.01292f, 1e-7f);  // linear segment: 12.92 x
}

TEST(ImageIo, ExrRoundTripIsBitExact) {
    ScratchDir dir("exr_round_trip");
    const lh::ImageRGB image = sampleImage();
    lh::writeImage(image, dir.file("a.exr"), 0.25f);  // exposure must not touch EXR
    const lh::ImageRGB back = lh::readImage(dir.file("a.exr"));
    ASSERT_EQ(back.width, image.width);
    ASSERT_EQ(back.height, image.height);
    ASSERT_EQ(back.pixels.size(), image.pixels.size());
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        EXPECT_EQ(bitsOf(back.pixels[i]), bitsOf(image.pixels[i])) << "index " << i;
}

TEST(ImageIo, ExrWithDataWindowHalfYOnlyReadsAsGrey) {
    ScratchDir dir("exr_y_only");
    const std::string path = dir.file("y.exr");
    // A 3x2 HALF luminance image whose data window starts at (10, 20), written directly.
    const Imath::Box2i window(Imath::V2i(10, 20), Imath::V2i(12, 21));
    Imf::Header header(Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(99, 99)), window);
    header.channels().insert("Y", Imf::Channel(Imf::HALF));
    const std::vector<half> y = {half(0.5f),    half(2.0f), half(0.25f),
                                 half(1024.0f), half(0.0f), half(-1.0f)};
    Imf::FrameBuffer frame;
    frame.insert("Y", Imf::Slice::Make(Imf::HALF, y.data(), window));
    {
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(2);
    }
    const lh::ImageRGB image = lh::readImage(path);
    ASSERT_EQ(image.width, 3);
    ASSERT_EQ(image.height, 2);
    for (int py = 0; py < 2; ++py)
        for (int px = 0; px < 3; ++px)
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(image.at(px, py)[c], float(y[py * 3 + px])) << px << "," << py;
}

TEST(ImageIo, PngRoundTripIsWithinHalfAStep) {
    ScratchDir dir("png_round_trip");
    lh::ImageRGB image(16, 4);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = float(i) / float(image.pixels.size() - 1);  // ramp over [0,1]
    image.pixels[0] = -1.0f;                                          // clamps to 0
    image.pixels[1] = 2.0f;                                           // clamps to 1
    image.pixels[2] = std::numeric_limits<float>::quiet_NaN();        // maps to 0
    lh::writeImage(image, dir.file("a.png"));
    const lh::ImageRGB back = lh::readImage(dir.file("a.png"));
    ASSERT_EQ(back.width, image.width);
    ASSERT_EQ(back.height, image.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const float v = image.pixels[i];
        const float clamped = v > 0.0f ? std::min(v, 1.0f) : 0.0f;
        EXPECT_NEAR(lh::srgbEncode(back.pixels[i]), lh::srgbEncode(clamped), 0.5f / 255 + 1e-5f)
            << "index " << i;
    }
    EXPECT_EQ(back.pixels[0], 0.0f);
    EXPECT_EQ(back.pixels[1], 1.0f);
    EXPECT_EQ(back.pixels[2], 0.0f);
}

TEST(ImageIo, PngExposureScalesBeforeClamping) {
    ScratchDir dir("png_exposure");
    lh::ImageRGB image(2, 1);
    std::fill(image.pixels.begin(), image.pixels.end(), 4.0f);
    image.pixels[3] = 1.0f;  // becomes 0.25 linear
    lh::writePng(image, dir.file("a.png"), 0.25f);
    const lh::ImageRGB back = lh::readImage(dir.file("a.png"));
    EXPECT_EQ(back.pixels[0], 1.0f);
    EXPECT_EQ(back.pixels[2], 1.0f);
    EXPECT_NEAR(lh::srgbEncode(back.pixels[3]), lh::srgbEncode(0.25f), 0.5f / 255 + 1e-5f);
    EXPECT_THROW(lh::writePng(image, dir.file("b.png"), 0.0f), lh::InputError);
    EXPECT_THROW(lh::writePng(image, dir.file("b.png"), std::nanf("")), lh::InputError);
}

TEST(ImageIo, ReadingMissingCorruptOrUnsupportedFilesThrowsFileError) {
    ScratchDir dir("read_errors");
    EXPECT_THROW(lh::readImage(dir.file("missing.exr")), lh::FileError);
    EXPECT_THROW(lh::readImage(dir.file("missing.png")), lh::FileError);
    fs::create_directory(dir.path / "folder.exr");
    EXPECT_THROW(lh::readImage(dir.file("folder.exr")), lh::FileError);

    writeBytes(dir.file("x.exr"), randomBytes(4096));
    writeBytes(dir.file("x.png"), randomBytes(4096));
    writeBytes(dir.file("empty.exr"), {});
    EXPECT_THROW(lh::readImage(dir.file("x.exr")), lh::FileError);
    EXPECT_THROW(lh::readImage(dir.file("x.png")), lh::FileError);
    EXPECT_THROW(lh::readImage(dir.file("empty.exr")), lh::FileError);

    // A valid EXR cut in half: header intact, pixel data missing.
    lh::writeExr(sampleImage(), dir.file("whole.exr"));
    const auto size = fs::file_size(dir.file("whole.exr"));
    fs::copy_file(dir.file("whole.exr"), dir.file("cut.exr"));
    fs::resize_file(dir.file("cut.exr"), size / 2);
    EXPECT_THROW(lh::readImage(dir.file("cut.exr")), lh::FileError);

    lh::writePng(sampleImage(), dir.file("real.png"));
    fs::copy_file(dir.file("real.png"), dir.file("real.bmp"));
    EXPECT_THROW(lh::readImage(dir.file("real.bmp")), lh::FileError);
}

TEST(ImageIo, TruncatedPngAndJpegAreNamedAsSuch) {
    ScratchDir dir("truncated");
    lh::writePng(sampleImage(), dir.file("whole.png"));
    fs::copy_file(dir.file("whole.png"), dir.file("cut.png"));
    fs::resize_file(dir.file("cut.png"), fs::file_size(dir.file("whole.png")) / 2);
    // A JPEG that stops right after its start-of-image and a first marker.
    writeBytes(dir.file("cut.jpg"),
               {char(0xFF), char(0xD8), char(0xFF), char(0xE0), 0, 16, 'J', 'F'});
    writeBytes(dir.file("text.png"), {'h', 'e', 'l', 'l', 'o'});
    const auto messageOf = [](const std::string& path) {
        try {
            lh::readImage(path);
        } catch (const lh::FileError& e) {
            return std::string(e.what());
        }
        return std::string("no exception");
    };
    EXPECT_NE(messageOf(dir.file("cut.png")).find("cut.png': truncated or corrupt PNG"),
              std::string::npos)
        << messageOf(dir.file("cut.png"));
    EXPECT_NE(messageOf(dir.file("cut.jpg")).find("cut.jpg': truncated or corrupt JPEG"),
              std::string::npos)
        << messageOf(dir.file("cut.jpg"));
    EXPECT_NE(messageOf(dir.file("text.png")).find("not a PNG or JPEG file"), std::string::npos)
        << messageOf(dir.file("text.png"));
}

// stb_image decodes more formats than PNG and JPEG, whatever the file's name: the fuzzer's
// 13-byte PGM header named .png (fuzz/corpus/image_png/crash_pgm_named_png_huge.png) made it
// allocate 0.8 GB, and the float image then 3.1 GB. Only PNG and JPEG content reaches stb now.
TEST(ImageIo, OtherFormatsUnderAPngOrJpegNameAreRefusedUnread) {
    ScratchDir dir("other_formats");
    const std::string pgmHeader =
        "P55100\x0b"
        "510353";  // a binary PGM header: 260 million pixels
    writeBytes(dir.file("huge.png"), std::vector<char>(pgmHeader.begin(), pgmHeader.end()));
    // A complete 1 x 1 grey PGM, which stb would decode: refused all the same.
    const std::string pgm = std::string("P5 1 1 255\n") + char(200);
    writeBytes(dir.file("grey.jpg"), std::vector<char>(pgm.begin(), pgm.end()));
    for (const char* name : {"huge.png", "grey.jpg"}) {
        try {
            lh::readImage(dir.file(name));
            FAIL() << name << " was read";
        } catch (const lh::FileError& e) {
            EXPECT_NE(std::string(e.what()).find("not a PNG or JPEG file"), std::string::npos)
                << e.what();
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    }
}

TEST(ImageIo, ErrorMessagesAreOneLineAndNameTheFile) {
    ScratchDir dir("messages");
    writeBytes(dir.file("x.exr"), randomBytes(4096));
    try {
        lh::readImage(dir.file("x.exr"));
        FAIL() << "no exception";
    } catch (const lh::FileError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(dir.file("x.exr")), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(ImageIo, ReadingAbsurdSizesThrowsResourceError) {
    ScratchDir dir("absurd");
    // A PNG whose header claims 16385 x 16384 pixels (> 2^28, yet under stb's own 2^30-byte
    // limit); stb does not check the CRC.
    lh::writePng(lh::ImageRGB(1, 1), dir.file("a.png"));
    std::vector<char> bytes(fs::file_size(dir.file("a.png")));
    std::ifstream(dir.file("a.png"), std::ios::binary)
        .read(bytes.data(), std::streamsize(bytes.size()));
    const unsigned char width[4] = {0x00, 0x00, 0x40, 0x01};   // big-endian 16385
    const unsigned char height[4] = {0x00, 0x00, 0x40, 0x00};  // big-endian 16384
    std::memcpy(&bytes[16], width, 4);                         // IHDR width
    std::memcpy(&bytes[20], height, 4);                        // IHDR height
    writeBytes(dir.file("huge.png"), bytes);
    EXPECT_THROW(lh::readImage(dir.file("huge.png")), lh::ResourceError);

    // An EXR header claiming 16385 x 16384 pixels, with no pixel data written.
    const std::string exr = dir.file("huge.exr");
    {
        Imf::Header header(16385, 16384);
        header.channels().insert("R", Imf::Channel(Imf::HALF));
        Imf::OutputFile file(exr.c_str(), header);
    }
    EXPECT_THROW(lh::readImage(exr), lh::ResourceError);
}

TEST(ImageIo, WritingRefusesBadImagesAndFormats) {
    ScratchDir dir("write_errors");
    EXPECT_THROW(lh::writeImage(sampleImage(), dir.file("a.bmp")), lh::InputError);
    EXPECT_THROW(lh::writeImage(sampleImage(), dir.file("noextension")), lh::InputError);
    EXPECT_THROW(lh::writeImage(lh::ImageRGB(), dir.file("a.exr")), lh::InputError);
    EXPECT_THROW(lh::writeImage(lh::ImageRGB(0, 3), dir.file("a.png")), lh::InputError);
    lh::ImageRGB wrongSize(4, 4);
    wrongSize.pixels.pop_back();
    EXPECT_THROW(lh::writeImage(wrongSize, dir.file("a.exr")), lh::InputError);
    EXPECT_THROW(lh::writeImage(wrongSize, dir.file("a.png")), lh::InputError);
    EXPECT_TRUE(listDir(dir.path).empty());
}

TEST(ImageIo, WritingIntoMissingDirectoryThrowsFileErrorAndCreatesNothing) {
    ScratchDir dir("missing_dir");
    const fs::path missing = dir.path / "does_not_exist";
    EXPECT_THROW(lh::writeImage(sampleImage(), (missing / "a.exr").string()), lh::FileError);
    EXPECT_THROW(lh::writeImage(sampleImage(), (missing / "a.png").string()), lh::FileError);
    EXPECT_FALSE(fs::exists(missing));
    EXPECT_TRUE(listDir(dir.path).empty());
}

TEST(ImageIo, SuccessfulWritesLeaveNoTemporaryFile) {
    ScratchDir dir("no_temporaries");
    lh::writeImage(sampleImage(), dir.file("a.exr"));
    lh::writeImage(sampleImage(), dir.file("a.png"));
    lh::writeImage(sampleImage(), dir.file("a.exr"));  // overwriting an existing file
    EXPECT_EQ(listDir(dir.path), (std::vector<std::string>{"a.exr", "a.png"}));
}
