// lighthouse-fuzz-seeds FUZZ_DIR: writes the binary seeds of the fuzz corpora (small .vdb, PNG,
// JPEG and EXR files, good ones and broken ones) into FUZZ_DIR/corpus/<target>/, and the two
// exports the DCC manifest target reads (FUZZ_DIR/dcc_fixture/<program>/, their manifests
// going to corpus/dcc_manifest/ as seeds). Run by hand when a format changes, not by the
// build: an export's id is random, so every run gives a new fixture (and manifests to match).
#include "core/errors.h"
#include "houdini_export/dcc_export.h"
#include "image/image_io.h"
#include "vdb/example_volume.h"
#include "vdb/volume_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <openvdb/io/File.h>
#include <stb/stb_image_write.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

std::vector<char> readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& path, const std::vector<char>& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out) throw lh::FileError("cannot write '" + path.string() + "'");
}

// Broken copies of a good seed: its first `keep` bytes, and the whole with one byte inverted
// at `flipAt` (a fraction of the size).
void writeBroken(const fs::path& good, const std::string& stem, std::size_t keep, double flipAt) {
    std::vector<char> bytes = readBytes(good);
    writeBytes(good.parent_path() / ("broken_" + stem + "_truncated" + good.extension().string()),
               std::vector<char>(bytes.begin(), bytes.begin() + std::min(keep, bytes.size())));
    bytes[std::size_t(flipAt * double(bytes.size() - 1))] ^= char(0xFF);
    writeBytes(good.parent_path() / ("broken_" + stem + "_flipped" + good.extension().string()),
               bytes);
}

// A small colourful image: a gradient with one bright pixel.
lh::ImageRGB gradient(int width, int height) {
    lh::ImageRGB image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float* p = image.at(x, y);
            p[0] = float(x) / float(width);
            p[1] = float(y) / float(height);
            p[2] = 0.25f;
        }
    image.at(width / 2, height / 2)[0] = 40.f;  // beyond [0, 1]: EXR keeps it, PNG clips it
    return image;
}

// 8-bit pixels of `channels` channels (grey, grey + alpha, RGB, RGBA).
std::vector<unsigned char> bytePixels(int width, int height, int channels) {
    std::vector<unsigned char> pixels(std::size_t(width) * height * channels);
    for (std::size_t i = 0; i < pixels.size(); ++i)
        pixels[i] = static_cast<unsigned char>(i * 37 % 256);
    return pixels;
}

void writePngs(const fs::path& dir) {
    fs::create_directories(dir);
    lh::writePng(gradient(6, 4), (dir / "rgb.png").string());
    for (int channels : {1, 2, 4}) {
        const auto pixels = bytePixels(5, 3, channels);
        stbi_write_png((dir / ("channels_" + std::to_string(channels) + ".png")).c_str(), 5, 3,
                       channels, pixels.data(), 5 * channels);
    }
    writeBroken(dir / "rgb.png", "rgb", 60, 0.6);
}

// A JPEG with an EXIF block saying the photo is rotated (Orientation 6, "rotate 90 degrees
// clockwise to view"): the APP1 segment goes right after the SOI marker.
void writeRotatedJpeg(const fs::path& plain, const fs::path& out) {
    const std::vector<char> jpeg = readBytes(plain);
    const unsigned char tiff[] = {'I',  'I',  42, 0, 8, 0, 0, 0,  // little-endian TIFF header
                                  1,    0,                        // one IFD entry
                                  0x12, 0x01, 3,  0, 1, 0, 0, 0,
                                  6,    0,    0,  0,   // Orientation, SHORT, 1, 6
                                  0,    0,    0,  0};  // no next IFD
    std::vector<char> app1 = {'E', 'x', 'i', 'f', 0, 0};
    app1.insert(app1.end(), std::begin(tiff), std::end(tiff));
    const std::size_t length = app1.size() + 2;  // the length field counts itself
    std::vector<char> bytes(jpeg.begin(), jpeg.begin() + 2);
    bytes.insert(bytes.end(), {char(0xFF), char(0xE1), char(length >> 8), char(length & 0xFF)});
    bytes.insert(bytes.end(), app1.begin(), app1.end());
    bytes.insert(bytes.end(), jpeg.begin() + 2, jpeg.end());
    writeBytes(out, bytes);
}

void writeJpegs(const fs::path& dir) {
    fs::create_directories(dir);
    for (int channels : {1, 3}) {
        const auto pixels = bytePixels(7, 5, channels);
        stbi_write_jpg((dir / ("channels_" + std::to_string(channels) + ".jpg")).c_str(), 7, 5,
                       channels, pixels.data(), 90);
    }
    writeRotatedJpeg(dir / "channels_3.jpg", dir / "exif_rotated.jpg");
    writeBroken(dir / "channels_3.jpg", "rgb", 200, 0.7);
}

// A half-precision grey (Y) EXR whose data window does not start at the origin.
void writeGreyExr(const fs::path& path) {
    const Imath::Box2i window(Imath::V2i(-2, 3), Imath::V2i(2, 5));  // 5 x 3 pixels
    Imf::Header header(window, window);
    header.channels().insert("Y", Imf::Channel(Imf::HALF));
    std::vector<half> pixels(15);
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = half(float(i) * 0.5f);
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer frame;
    frame.insert(
        "Y", Imf::Slice::Make(Imf::HALF, pixels.data(), window, sizeof(half), 5 * sizeof(half)));
    file.setFrameBuffer(frame);
    file.writePixels(3);
}

void writeExrs(const fs::path& dir) {
    fs::create_directories(dir);
    lh::writeExr(gradient(6, 4), (dir / "rgb_float.exr").string());
    writeGreyExr(dir / "grey_half_offset_window.exr");
    writeBroken(dir / "rgb_float.exr", "rgb", 300, 0.8);
}

// The example room, tiny: 2 levels of 4^3 voxels (a few kB).
lh::LightingVolume tinyVolume() { return lh::makeExampleVolume(2, 4); }

// A small MPI in an 8 x 6 version of the example's reference camera, with a few opaque pixels.
lh::Mpi tinyMpi() {
    lh::Mpi mpi = lh::Mpi::create(lh::exampleCameras().ref.resized(8, 6), 1.0, 7.0, 2);
    for (int plane = 0; plane < 2; ++plane) {
        float* p = mpi.pixel(plane, 3 + plane, 2);
        p[0] = 0.8f, p[1] = 0.4f, p[2] = 0.1f, p[3] = 1.f;
    }
    return mpi;
}

void writeVdbs(const fs::path& dir) {
    fs::create_directories(dir);
    const lh::LightingVolume volume = tinyVolume();
    lh::saveVolume((dir / "example.vdb").string(), volume);
    lh::VolumeSaveOptions half;
    half.halfPrecision = true;
    lh::saveVolume((dir / "example_half.vdb").string(), volume, half);
    const lh::Mpi mpi = tinyMpi();
    lh::saveVdb((dir / "with_mpi.vdb").string(), &volume, &mpi);

    // Values the loader must sanitise: NaN, +Inf and negative voxels, and a NaN background.
    lh::LightingVolume bad = lh::makeExampleVolume(1, 4);
    auto d = bad.levels[0].density->getAccessor();
    d.setValue(openvdb::Coord(0, 0, 0), std::numeric_limits<float>::quiet_NaN());
    d.setValue(openvdb::Coord(1, 0, 0), std::numeric_limits<float>::infinity());
    d.setValue(openvdb::Coord(2, 0, 0), -1.f);
    bad.levels[0].color->getAccessor().setValue(openvdb::Coord(3, 0, 0),
                                                openvdb::Vec3s(-1.f, NAN, INFINITY));
    lh::saveVolume((dir / "non_finite.vdb").string(), bad);

    // Blender's names (one level, `density` and `color`), without lighthouse's metadata.
    openvdb::GridPtrVec grids;
    for (openvdb::GridBase::Ptr g : {openvdb::GridBase::Ptr(volume.levels[1].density->deepCopy()),
                                     openvdb::GridBase::Ptr(volume.levels[1].color->deepCopy())}) {
        g->clearMetadata();
        g->setName(g->isType<openvdb::FloatGrid>() ? "density" : "color");
        grids.push_back(g);
    }
    openvdb::io::File((dir / "blender_names.vdb").string()).write(grids);
    writeBroken(dir / "with_mpi.vdb", "with_mpi", 400, 0.5);
}

void writeExports(const fs::path& fuzzDir) {
    const lh::LightingVolume volume = tinyVolume();
    const lh::Mpi mpi = tinyMpi();
    for (const auto& [dcc, name] :
         {std::pair{lh::Dcc::Houdini, "houdini"}, std::pair{lh::Dcc::Blender, "blender"}}) {
        const fs::path dir = fuzzDir / "dcc_fixture" / name;
        fs::create_directories(dir.parent_path());
        lh::DccExportOptions options;
        options.dcc = dcc;
        options.replaceExisting = true;
        lh::exportForDcc(volume, dir.string(), options, &mpi);
        const fs::path seeds = fuzzDir / "corpus" / "dcc_manifest";
        fs::create_directories(seeds);
        fs::rename(dir / "manifest.json", seeds / (std::string(name) + ".json"));
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: lighthouse-fuzz-seeds FUZZ_DIR (the repository's fuzz/ folder)\n";
        return 2;
    }
    try {
        openvdb::initialize();
        const fs::path fuzzDir = argv[1];
        writeVdbs(fuzzDir / "corpus" / "vdb_volume");
        writePngs(fuzzDir / "corpus" / "image_png");
        writeJpegs(fuzzDir / "corpus" / "image_jpeg");
        writeExrs(fuzzDir / "corpus" / "image_exr");
        writeExports(fuzzDir);
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "lighthouse-fuzz-seeds: error: " << e.what() << "\n";
        return 1;
    }
}
