#include "image/image_io.h"

#include "core/atomic_file.h"
#include "core/errors.h"
#include "image/image_orientation.h"
#include "image/srgb8.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <system_error>
#include <vector>

namespace lh {

namespace {

constexpr std::size_t kPixelBytes = 3 * sizeof(float);  // one interleaved RGB pixel
const char* const kRgbNames[3] = {"R", "G", "B"};

std::string sizeText(std::int64_t width, std::int64_t height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

// Library messages may span lines; ours are one line so the CLI can print them as is.
std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    return text;
}

// Writes refuse what readImage would refuse, so every written file can be read back.
void checkWritable(const ImageRGB& image, const std::string& path) {
    const std::string prefix = "cannot write '" + path + "': ";
    if (image.width <= 0 || image.height <= 0)
        throw InputError(prefix + "image is empty (" + sizeText(image.width, image.height) + ")");
    const std::size_t expected = std::size_t(image.width) * std::size_t(image.height) * 3;
    if (image.pixels.size() != expected)
        throw InputError(prefix + "image is " + sizeText(image.width, image.height) +
                         " but holds " + std::to_string(image.pixels.size()) +
                         " floats instead of " + std::to_string(expected));
    if (image.width > kMaxImagePixels / image.height)
        throw ResourceError(prefix + "image is " + sizeText(image.width, image.height) +
                            ", more than " + std::to_string(kMaxImagePixels) + " pixels");
}

// Checked before allocating, because the size comes from an untrusted header.
void checkReadableSize(std::int64_t width, std::int64_t height, const std::string& path) {
    const std::string prefix = "cannot read '" + path + "': ";
    if (width <= 0 || height <= 0)
        throw FileError(prefix + "invalid image size " + sizeText(width, height));
    if (width > kMaxImagePixels / height)
        throw ResourceError(prefix + "image is " + sizeText(width, height) + ", more than " +
                            std::to_string(kMaxImagePixels) + " pixels");
}

ImageRGB readExr(const std::string& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
        const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
        checkReadableSize(width, height, path);

        const Imf::ChannelList& channels = file.header().channels();
        const bool grey =
            !channels.findChannel("R") && !channels.findChannel("G") && !channels.findChannel("B");
        if (grey && !channels.findChannel("Y"))
            throw FileError("cannot read '" + path + "': it has no R, G, B or Y channel");

        // OpenEXR converts every pixel type to FLOAT and fills absent channels with 0.
        // Slice::Make offsets the pointer by the data window origin.
        ImageRGB image(static_cast<int>(width), static_cast<int>(height));  // fits: checked above
        const std::size_t rowBytes = kPixelBytes * std::size_t(width);
        auto slice = [&](int c) {
            return Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, window, kPixelBytes,
                                    rowBytes);
        };
        Imf::FrameBuffer frame;
        if (grey) {
            frame.insert("Y", slice(0));
        } else {
            for (int c = 0; c < 3; ++c) frame.insert(kRgbNames[c], slice(c));
        }
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);

        if (grey) {
            for (std::size_t i = 0; i < image.pixels.size(); i += 3)
                image.pixels[i + 1] = image.pixels[i + 2] = image.pixels[i];
        }
        return image;
    } catch (const Error&) {  // ours (e.g. ResourceError) pass through unchanged
        throw;
    } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
        throw FileError("cannot read '" + path + "': " + oneLine(e.what()));
    }
}

std::string stbReason() {
    const char* reason = stbi_failure_reason();
    return reason ? reason : "unknown decoder error";
}

// The format a file's first bytes announce: "PNG", "JPEG" or "" (neither).
std::string announcedFormat(const std::string& path) {
    unsigned char magic[4] = {0, 0, 0, 0};
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return "";
    const std::size_t n = std::fread(magic, 1, sizeof magic, f);
    std::fclose(f);
    if (n == 4 && magic[0] == 0x89 && magic[1] == 'P' && magic[2] == 'N' && magic[3] == 'G')
        return "PNG";
    if (n >= 3 && magic[0] == 0xFF && magic[1] == 0xD8 && magic[2] == 0xFF) return "JPEG";
    return "";
}

// stb's terse reasons ("outofdata", "bad huffman code") as one line a user can act on: a file
// that starts like a PNG or JPEG but does not decode is truncated or corrupt.
[[noreturn]] void throwStbFailure(const std::string& path) {
    const std::string reason = stbReason(), format = announcedFormat(path);
    if (!format.empty())
        throw FileError("'" + path + "': truncated or corrupt " + format +
                        " (the decoder stopped at: " + reason + ")");
    throw FileError("cannot read '" + path + "': not a PNG or JPEG file (" + reason + ")");
}

ImageRGB readStb(const std::string& path) {
    // stb_image also decodes BMP, GIF, PSD, PIC, PNM, TGA and HDR, whatever the file is called;
    // only PNG and JPEG reach it. A 13-byte PGM header named .png made it allocate 3.9 GB
    // (fuzz/corpus/image_png/crash_pgm_named_png_huge.png).
    if (announcedFormat(path).empty())
        throw FileError("cannot read '" + path +
                        "': not a PNG or JPEG file (it starts with neither signature)");
    int width = 0, height = 0, fileChannels = 0;
    // Header only: the size is checked before stb allocates the pixels.
    if (!stbi_info(path.c_str(), &width, &height, &fileChannels)) throwStbFailure(path);
    checkReadableSize(width, height, path);

    const int wantedChannels = 3;  // stb converts grey and alpha images to RGB
    std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> bytes(
        stbi_load(path.c_str(), &width, &height, &fileChannels, wantedChannels), &stbi_image_free);
    if (!bytes) throwStbFailure(path);

    // Photos are used upright. Turned while converted: a turned copy of the float image had
    // readImage hold 27 bytes a pixel, 3.6 GB for the 585-byte JPEG of 2043 x 65528 pixels that
    // the JPEG fuzz target found (fuzz/corpus/image_jpeg/crash_exif_flipped_134_megapixels.jpg).
    const stbi_uc* stored = bytes.get();
    return uprightImage(width, height, exifOrientation(path), [&](int sx, int sy, float* to) {
        const stbi_uc* from = stored + (std::size_t(sy) * std::size_t(width) + std::size_t(sx)) * 3;
        to[0] = linearFromSrgb8(from[0]);
        to[1] = linearFromSrgb8(from[1]);
        to[2] = linearFromSrgb8(from[2]);
    });
}

}  // namespace

// Evaluated in double so that decode(encode(x)) returns x to ~1e-7.
float srgbEncode(float linear) {
    const double v = linear;
    return float(v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055);
}

float srgbDecode(float encoded) {
    const double v = encoded;
    return float(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
}

void writeExr(const ImageRGB& image, const std::string& path) {
    checkWritable(image, path);
    AtomicOutput out(path);
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;  // lossless
        Imf::FrameBuffer frame;
        for (int c = 0; c < 3; ++c) {
            header.channels().insert(kRgbNames[c], Imf::Channel(Imf::FLOAT));
            frame.insert(kRgbNames[c],
                         Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, header.dataWindow(),
                                          kPixelBytes, kPixelBytes * std::size_t(image.width)));
        }
        Imf::OutputFile file(out.tempPath().c_str(), header);  // closed at end of scope
        file.setFrameBuffer(frame);
        file.writePixels(image.height);
    } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
        throw FileError("cannot write '" + path + "': " + oneLine(e.what()));
    }
    out.commit();
}

void writePng(const ImageRGB& image, const std::string& path, float exposure) {
    checkWritable(image, path);
    if (!(std::isfinite(exposure) && exposure > 0.0f))
        throw InputError("cannot write '" + path + "': exposure must be finite and > 0, got " +
                         std::to_string(exposure));
    AtomicOutput out(path);

    std::vector<unsigned char> bytes(image.pixels.size());
    for (std::size_t i = 0; i < bytes.size(); ++i)
        bytes[i] = srgb8FromLinear(image.pixels[i] * exposure);
    if (!stbi_write_png(out.tempPath().c_str(), image.width, image.height, 3, bytes.data(),
                        image.width * 3))
        throw FileError("cannot write '" + path + "': PNG encoder failed");
    out.commit();
}

void writeImage(const ImageRGB& image, const std::string& path, float exposure) {
    const std::string ext = fileExtension(path);
    if (ext == ".exr")
        writeExr(image, path);
    else if (ext == ".png")
        writePng(image, path, exposure);
    else
        throw InputError("unsupported output format '" + ext + "' for '" + path +
                         "': use .exr or .png");
}

ImageRGB readImage(const std::string& path) {
    const std::string ext = fileExtension(path);
    const bool exr = ext == ".exr";
    if (!exr && ext != ".png" && ext != ".jpg" && ext != ".jpeg")
        throw FileError("cannot read '" + path + "': unsupported image format '" + ext +
                        "', use .exr, .png, .jpg or .jpeg");
    // Checked here for a clear message: the decoders report a missing file vaguely.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw FileError(
            "cannot read '" + path +
            "': " + (std::filesystem::exists(path, ec) ? "not a regular file" : "no such file"));
    return exr ? readExr(path) : readStb(path);
}

}  // namespace lh
