#include "net/training_data.h"

#include "core/errors.h"
#include "render/image_io.h"
#include "render/metrics.h"

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;

namespace lh::net {

std::vector<std::string> listExamples(const std::string& dataDir) {
    if (!fs::is_directory(dataDir))
        throw FileError("data directory '" + dataDir + "' not found (make one with 'lighthouse synth')");
    std::vector<std::string> out;
    for (const auto& entry : fs::directory_iterator(dataDir))
        if (entry.is_directory() && fs::is_regular_file(entry.path() / "cameras.json"))
            out.push_back(entry.path().string());
    std::sort(out.begin(), out.end());
    if (out.empty())
        throw FileError("'" + dataDir + "' holds no examples (sub-directories with cameras.json); make some with 'lighthouse synth'");
    return out;
}

TrainingExample loadExample(const std::string& directory, bool withMasks) {
    const fs::path dir(directory);
    TrainingExample ex;
    ex.directory = directory;
    ex.cameras = loadCamerasFile((dir / "cameras.json").string());
    if (!ex.cameras.src || !ex.cameras.tgt || !ex.cameras.near || !ex.cameras.far)
        throw FileError("'" + (dir / "cameras.json").string() + "' lacks src, tgt, near or far: not a training example");
    ex.ref = readImage((dir / "ref.png").string());
    ex.src = readImage((dir / "src.png").string());
    ex.tgt = readImage((dir / "tgt.png").string());
    for (const auto& e : ex.cameras.envmaps) {
        ex.envmaps.push_back(readImage((dir / e.file).string()));
        if (withMasks) {
            const std::string stem = fs::path(e.file).stem().string();
            ex.masks.push_back(loadMask((dir / (stem + "_mask.png")).string(), ex.envmaps.back().width,
                                        ex.envmaps.back().height));
        }
    }
    if (ex.envmaps.empty()) throw FileError("'" + directory + "' has no ground-truth envmaps");
    return ex;
}

}  // namespace lh::net
