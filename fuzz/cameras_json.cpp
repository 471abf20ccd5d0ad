// cameras.json (core/camera.h): parsing and validation. A bad file must be refused with a
// FileError or InputError; a file that is accepted must survive being written back and read
// again unchanged (the tools rewrite cameras.json, e.g. `lighthouse cameras`). The same text is
// also read as one camera, the form volumes keep in their metadata.
#include "core/camera.h"
#include "core/errors.h"
#include "fuzz/fuzz_input.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const lh::CamerasFile cameras = lh::parseCamerasJson(text, "cameras.json");
        const std::string written = lh::camerasToJson(cameras);
        lh::CamerasFile again;
        try {
            again = lh::parseCamerasJson(written, "written");
        } catch (const lh::Error& e) {
            lh::fuzz::fail(std::string("an accepted cameras.json is refused once written back: ") +
                           e.what());
        }
        if (lh::camerasToJson(again) != written)
            lh::fuzz::fail("cameras.json changes when written back and read");
    } catch (const lh::Error&) {
    }
    try {
        const lh::PinholeCamera camera = lh::cameraFromJson(text, "camera metadata");
        const std::string written = lh::cameraToJson(camera);
        if (lh::cameraToJson(lh::cameraFromJson(written, "written")) != written)
            lh::fuzz::fail("a camera changes when written back and read");
    } catch (const lh::Error&) {
    }
    return 0;
}
