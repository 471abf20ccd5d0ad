// JPEGs with chosen EXIF tags, made by the tests: stb_image_write encodes the pixels, libexif
// builds the EXIF block, which goes in as the APP1 segment right after the JPEG's SOI marker.
// Link the test with PkgConfig::EXIF and stb.
#pragma once

#include "tests/support/temp_path.h"

#include <gtest/gtest.h>
#include <libexif/exif-data.h>
#include <stb/stb_image_write.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace lh::test {

struct ExifTags {
    std::optional<int> focal35mm;     // SHORT
    std::optional<double> focalMm;    // RATIONAL (x1000)
    std::optional<double> planeXRes;  // RATIONAL, per unit
    std::optional<int> planeUnit;     // SHORT: 2 inch, 3 cm
    std::optional<int> pixelXDimension;
    std::optional<int> orientation;  // SHORT, IFD 0
};

inline void setNumber(ExifData* d, ExifIfd ifd, ExifTag tag, double value) {
    ExifEntry* e = exif_entry_new();
    exif_content_add_entry(d->ifd[ifd], e);  // first, so that it knows the byte order
    exif_entry_initialize(e, tag);
    const ExifByteOrder order = exif_data_get_byte_order(d);
    switch (e->format) {
        case EXIF_FORMAT_SHORT:
            exif_set_short(e->data, order, ExifShort(value));
            break;
        case EXIF_FORMAT_LONG:
            exif_set_long(e->data, order, ExifLong(value));
            break;
        case EXIF_FORMAT_RATIONAL:
            exif_set_rational(e->data, order,
                              ExifRational{ExifLong(std::lround(value * 1000)), 1000});
            break;
        default:
            ADD_FAILURE() << "unexpected EXIF format for tag " << tag;
    }
    exif_entry_unref(e);
}

inline std::vector<unsigned char> exifBlock(const ExifTags& t) {
    ExifData* d = exif_data_new();
    exif_data_set_byte_order(d, EXIF_BYTE_ORDER_INTEL);
    if (t.orientation) setNumber(d, EXIF_IFD_0, EXIF_TAG_ORIENTATION, *t.orientation);
    if (t.focal35mm) setNumber(d, EXIF_IFD_EXIF, EXIF_TAG_FOCAL_LENGTH_IN_35MM_FILM, *t.focal35mm);
    if (t.focalMm) setNumber(d, EXIF_IFD_EXIF, EXIF_TAG_FOCAL_LENGTH, *t.focalMm);
    if (t.planeXRes) setNumber(d, EXIF_IFD_EXIF, EXIF_TAG_FOCAL_PLANE_X_RESOLUTION, *t.planeXRes);
    if (t.planeUnit)
        setNumber(d, EXIF_IFD_EXIF, EXIF_TAG_FOCAL_PLANE_RESOLUTION_UNIT, *t.planeUnit);
    if (t.pixelXDimension)
        setNumber(d, EXIF_IFD_EXIF, EXIF_TAG_PIXEL_X_DIMENSION, *t.pixelXDimension);
    unsigned char* buf = nullptr;
    unsigned int size = 0;
    exif_data_save_data(d, &buf, &size);  // starts with "Exif\0\0", then the TIFF structure
    std::vector<unsigned char> block(buf, buf + size);
    std::free(buf);
    exif_data_unref(d);
    return block;
}

inline void appendBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    out->insert(out->end(), static_cast<unsigned char*>(data),
                static_cast<unsigned char*>(data) + size);
}

// A width x height JPEG of `rgb` (8-bit, interleaved; a gradient when empty), carrying `tags`
// (no EXIF at all when nullopt).
inline std::string makeJpeg(const std::string& name, int width, int height,
                            std::optional<ExifTags> tags, std::vector<unsigned char> rgb = {}) {
    if (rgb.empty()) {
        rgb.resize(std::size_t(width) * height * 3);
        for (std::size_t i = 0; i < rgb.size(); ++i)
            rgb[i] = static_cast<unsigned char>(i * 7 % 251);
    }
    std::vector<unsigned char> jpeg;
    EXPECT_TRUE(stbi_write_jpg_to_func(appendBytes, &jpeg, width, height, 3, rgb.data(), 90));
    if (tags) {
        const std::vector<unsigned char> block = exifBlock(*tags);
        const std::size_t length = block.size() + 2;  // the length field counts itself
        std::vector<unsigned char> app1 = {0xFF, 0xE1, static_cast<unsigned char>(length >> 8),
                                           static_cast<unsigned char>(length & 0xFF)};
        app1.insert(app1.end(), block.begin(), block.end());
        jpeg.insert(jpeg.begin() + 2, app1.begin(), app1.end());  // after SOI (FF D8)
    }
    const std::string path = test::uniqueTempPath(name);
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(jpeg.data()), std::streamsize(jpeg.size()));
    return path;
}

}  // namespace lh::test
