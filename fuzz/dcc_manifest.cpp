// The manifest.json of a Blender or Houdini export (houdini_export/dcc_import.h importFromDcc),
// which a user may edit by hand. The input is the manifest; the level files (and mpi.vdb) are
// those of two real exports, fuzz/dcc_fixture/houdini and blender, copied once into this
// process's scratch folder, so that a manifest that names them reaches the grids, the checksums
// and the MPI. A bad manifest must be refused with a FileError or InputError.
#include "core/errors.h"
#include "fuzz/fuzz_input.h"
#include "houdini_export/dcc_import.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Export {
    lh::Dcc dcc;
    fs::path dir;  // in the scratch folder
};

const std::vector<Export>& fixtureExports() {
    static const std::vector<Export> exports = [] {
        std::vector<Export> all;
        for (const auto& [dcc, name] :
             {std::pair{lh::Dcc::Houdini, "houdini"}, std::pair{lh::Dcc::Blender, "blender"}}) {
            const fs::path from = fs::path(LIGHTHOUSE_SOURCE_DIR) / "fuzz" / "dcc_fixture" / name;
            const fs::path to = lh::fuzz::scratchDir() / name;
            fs::create_directories(to);
            std::error_code ec;
            fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::overwrite_existing,
                     ec);
            if (ec || !fs::exists(to / "level_0.vdb"))
                lh::fuzz::fail("cannot copy the export fixture " + from.string());
            all.push_back({dcc, to});
        }
        return all;
    }();
    return exports;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    for (const Export& e : fixtureExports()) {
        lh::fuzz::writeInput(data, size, e.dir.filename().string() + "/manifest.json");
        try {
            lh::DccImportReport report;
            lh::importFromDcc(e.dir.string(), e.dcc, &report);
        } catch (const lh::Error&) {
        }
    }
    return 0;
}
