// JPEG decoding (image/image_io.h readImage on a .jpg file): see image_fuzz.h.
#include "fuzz/image_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return lh::fuzz::readImageInput(data, size, "input.jpg", false);
}
