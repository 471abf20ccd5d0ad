// PNG decoding (image/image_io.h readImage on a .png file): see image_fuzz.h.
#include "fuzz/image_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return lh::fuzz::readImageInput(data, size, "input.png", false);
}
