// The three image targets: the input as a file of one extension, read by readImage
// (image/image_io.h), which must refuse a bad file with a FileError or ResourceError and
// return, for a good one, an image whose pixel count matches its size; PNG and JPEG must decode
// to values in [0, 1] (an EXR holds whatever floats the file has, NaN included).
#pragma once

#include "core/errors.h"
#include "fuzz/fuzz_input.h"
#include "image/image_io.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace lh::fuzz {

inline int readImageInput(const std::uint8_t* data, std::size_t size, const char* fileName,
                          bool exr) {
    const std::string path = writeInput(data, size, fileName);
    try {
        const ImageRGB image = readImage(path);
        if (image.width <= 0 || image.height <= 0 ||
            image.pixels.size() != std::size_t(image.width) * std::size_t(image.height) * 3)
            fail("a decoded image's pixels do not match its size");
        if (!exr)
            for (float v : image.pixels)
                if (!(v >= 0.f && v <= 1.f))
                    fail("an 8-bit image decoded to a value outside [0, 1]");
    } catch (const Error&) {
    }
    return 0;
}

}  // namespace lh::fuzz
