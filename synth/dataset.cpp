#include "synth/dataset.h"

#include "core/atomic_file.h"
#include "core/dataset_files.h"
#include "core/errors.h"
#include "core/random.h"
#include "image/contact_sheet.h"
#include "image/image_io.h"
#include "image/luminance.h"
#include "image/metrics.h"
#include "synth/oracle.h"
#include "synth/scene_generator.h"
#include "synth/scene_json.h"
#include "synth/scene_render.h"
#include "vdb/volume_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace lh::synth {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxAttempts = 25;             // scenes tried per example before giving up
constexpr double kMinCameraClearance = 0.3;  // metres from the reference camera to any solid
constexpr double kMinMedianDepth = 1.0;      // metres: rejects views that stare at a nearby wall
constexpr double kMinBrightness = 0.1;       // mean sRGB value of ref (the paper's rule)
constexpr double kMedianLuminance[2] = {0.05, 0.4};  // auto-exposure's range for ref's median
constexpr double kEnvmapClearance = 0.3;             // metres from an envmap point to any surface

// Why a scene was rejected (for the manifest's statistics).
struct Rejected : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void scale(ImageRGB& image, double factor) {
    for (float& v : image.pixels) v = float(v * factor);
}

// Envmap points where a user would insert an object: along rays through the central 80% of
// the reference image, at a depth drawn uniformly between max(0.5 m, 25%) and 85% of the
// distance to the surface seen there, at least 0.3 m from every surface and from each other.
// This spreads points over the whole depth range, near objects and far ones, instead of the
// paper's "beyond the median depth" rule, because users insert objects at every depth.
std::vector<Vec3d> envmapPoints(const Scene& scene, const RayTracer& tracer,
                                const PinholeCamera& ref, int count, Random& rng) {
    std::vector<Vec3d> points;
    for (int tries = 0; tries < 400 && int(points.size()) < count; ++tries) {
        const Vec3d dir = ref.pixelDirection(rng.uniform(0.1, 0.9) * ref.width,
                                             rng.uniform(0.1, 0.9) * ref.height);
        const RayHit hit = tracer.intersect(ref.position, dir, 0.0);
        if (!hit.hit) continue;
        const double lo = std::max(0.5, 0.25 * hit.t), hi = 0.85 * hit.t;
        if (hi <= lo) continue;
        const Vec3d p = ref.position + dir * rng.uniform(lo, hi);
        if (scene.distanceToSolid(p) < kEnvmapClearance) continue;
        bool crowded = false;
        for (const Vec3d& q : points) crowded |= (q - p).length() < 0.3;
        if (!crowded) points.push_back(p);
    }
    if (int(points.size()) < count) throw Rejected("no room for envmap points");
    return points;
}

}  // namespace

void SynthOptions::validate() const {
    if (count < 1 || count > 1000000) throw InputError("--count must be in [1, 1000000]");
    if (split != "train" && split != "test")
        throw InputError("--split must be train or test, got '" + split + "'");
    if (width < 16 || height < 16 || width > 4096 || height > 4096)
        throw InputError("--size must be between 16x16 and 4096x4096");
    if (envWidth != 2 * envHeight || envHeight < 4 || envHeight > 2048)
        throw InputError("--envmap-size must be W x H with W = 2 H and 4 <= H <= 2048");
    if (envmapsPerExample < 1 || envmapsPerExample > 16)
        throw InputError("--envmaps must be in [1, 16]");
    if (supersample < 1 || supersample > 8) throw InputError("--supersample must be in [1, 8]");
    if (out.empty()) throw InputError("-o/--output is required");
    if (oracleLevels < 0 || oracleLevels > 8) throw InputError("--oracle-levels must be in [0, 8]");
    if (oracleLevels > 0) VolumeLayout{20.0, oracleLevels, oracleResolution}.validate();
}

uint64_t exampleSeed(const std::string& split, uint64_t index) {
    return index * 2 + (split == "test" ? 1 : 0);
}

ExampleSummary writeExample(uint64_t seed, const std::string& directory, const SynthOptions& o,
                            PanoramaLibrary& panoramas) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<std::string> names = panoramas.names();
    for (const auto& n : names) panoramas.get(n);  // load before parallel work
    ExampleSummary summary;
    summary.id = fs::path(directory).filename().string();
    for (int attempt = 0; attempt < kMaxAttempts; ++attempt) {
        const uint64_t sceneSeed = mixSeed(seed, attempt);
        GeneratedScene gen = generateScene(sceneSeed, names, o.width, o.height, o.lampLayout);
        Scene& scene = gen.scene;
        const Rig& rig = gen.rig;
        try {
            if (scene.distanceToSolid(rig.ref.position) < kMinCameraClearance ||
                scene.distanceToSolid(rig.src.position) < kMinCameraClearance)
                throw Rejected("camera too close to a surface");
            const RayTracer tracer(scene);
            const ImageRGB depth = renderDepth(tracer, rig.ref);
            std::vector<float> depths;
            for (std::size_t i = 0; i < depth.pixels.size(); i += 3)
                depths.push_back(depth.pixels[i]);
            std::sort(depths.begin(), depths.end());
            if (!std::isfinite(depths.back())) throw Rejected("rays leave the room");
            if (depths[depths.size() / 2] < kMinMedianDepth) throw Rejected("facing a nearby wall");
            Random rng(mixSeed(sceneSeed, 0xE7));
            const std::vector<Vec3d> points =
                envmapPoints(scene, tracer, rig.ref, o.envmapsPerExample, rng);

            const RadianceField field(scene, tracer, panoramas, o.bake);
            // Auto-exposure as a camera meters: the reference view's median luminance lands
            // at kMedianLuminance[0]-[1] (log-uniform), whatever its lamps and windows do (they
            // clip). A mean would be ruled by the lamps: metering the mean at 0.18 left the
            // median at 0.008-0.2, 2.5x darker than the evaluation rooms' 0.05-0.39.
            ImageRGB ref = renderSceneView(tracer, field, rig.ref, o.supersample);
            std::vector<double> luminances;
            for (std::size_t i = 0; i < ref.pixels.size(); i += 3)
                luminances.push_back(rec709Luminance(&ref.pixels[i]));
            const auto middle = luminances.begin() + long(luminances.size() / 2);
            std::nth_element(luminances.begin(), middle, luminances.end());
            const double median = *middle;
            if (!(median > 0)) throw Rejected("black reference view");
            const double target =
                std::exp(rng.uniform(std::log(kMedianLuminance[0]), std::log(kMedianLuminance[1])));
            scene.exposure = target / median;
            scale(ref, scene.exposure);
            double brightness = 0;
            for (float v : ref.pixels) brightness += srgbEncode(std::clamp(v, 0.f, 1.f));
            if (brightness / ref.pixels.size() < kMinBrightness) throw Rejected("too dark");

            // Everything is rendered; write it under a temporary name, then rename.
            const fs::path final(directory),
                temp = final.parent_path() / ("." + summary.id + ".partial");
            fs::remove_all(temp);
            fs::create_directories(temp);
            const auto file = [&](const std::string& name) { return (temp / name).string(); };
            writeImage(ref, file(dataset::viewExr("ref")));
            writePng(ref, file(dataset::viewPng("ref")));
            for (const auto& [name, camera] :
                 {std::pair{"src", &rig.src}, std::pair{"tgt", &rig.tgt}}) {
                const ImageRGB view = renderSceneView(tracer, field, *camera, o.supersample);
                writeImage(view, file(dataset::viewExr(name)));
                writePng(view, file(dataset::viewPng(name)));
            }
            writeImage(depth, file(dataset::kDepth));
            CamerasFile cameras;
            cameras.ref = rig.ref;
            cameras.src = rig.src;
            cameras.tgt = rig.tgt;
            // Depth range seen by ref: 1st and 99th percentiles (docs/conventions.md#cameras).
            cameras.near = double(depths[depths.size() / 100]);
            cameras.far = double(depths[depths.size() * 99 / 100]);
            for (std::size_t k = 0; k < points.size(); ++k) {
                const std::string stem = dataset::envmapStem(k);
                SceneEnvmap env = renderSceneEnvmap(tracer, field, points[k], o.envWidth,
                                                    o.envHeight, rig.ref, o.supersample);
                writeImage(env.radiance, file(dataset::envmapExr(k)));
                writePng(env.radiance, file(dataset::envmapPng(k)));
                writePng(maskToImage(env.observed, o.envWidth, o.envHeight),
                         file(dataset::maskPng(stem)));
                writeImage(env.hitPositions, file(dataset::positionsExr(stem)));
                cameras.envmaps.push_back(
                    {points[k], dataset::envmapExr(k), dataset::positionsExr(stem)});
            }
            writeTextFile(file(dataset::kCameras), camerasToJson(cameras));
            writeTextFile(file(dataset::kScene), sceneToJson(scene, o.bake));
            if (o.oracleLevels > 0) {
                const VolumeLayout layout =
                    VolumeLayout::fromFarDepth(*cameras.far, o.oracleLevels, o.oracleResolution);
                VolumeSaveOptions half;
                half.halfPrecision = true;
                saveVolume(file(dataset::kOracle), oracleVolume(scene, field, layout), half);
            }
            fs::remove_all(final);
            fs::rename(temp, final);
            summary.seed = sceneSeed;
            summary.rejected = attempt;
            summary.texels = field.texelCount();
            summary.seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            return summary;
        } catch (const Rejected&) {
            continue;  // the next scene seed
        }
    }
    throw Error("example " + summary.id + ": no acceptable scene in " +
                std::to_string(kMaxAttempts) + " attempts");
}

namespace {

// The manifest's description of the data set, without timings or examples; every shard of a
// set must share it.
nlohmann::json datasetHeader(const SynthOptions& o) {
    nlohmann::json header = {{"generator_version", kGeneratorVersion},
                             {"split", o.split},
                             {"first_index", o.seed},
                             {"count", o.count},
                             {"view_size", {o.width, o.height}},
                             {"envmap_size", {o.envWidth, o.envHeight}},
                             {"envmaps_per_example", o.envmapsPerExample},
                             {"supersample", o.supersample},
                             {"bake",
                              {{"texel_size", o.bake.texelSize},
                               {"max_texels", o.bake.maxTexels},
                               {"gather_rays", o.bake.gatherRays},
                               {"light_samples", o.bake.lightSamples},
                               {"bounces", o.bake.bounces}}}};
    // Written only when not the default, so that sets made before the option keep their header.
    if (o.lampLayout == LampLayout::Room) header["lamp_layout"] = "room";
    return header;
}

std::string exampleId(int index) {
    char id[16];
    std::snprintf(id, sizeof id, "%06d", index);
    return id;
}

// A picture of the first examples: ref | src | env_0.
void writeContactSheet(const std::string& out, const std::vector<std::string>& dirs) {
    std::vector<std::vector<ImageRGB>> rows;
    for (std::size_t i = 0; i < std::min<std::size_t>(4, dirs.size()); ++i) {
        const fs::path d(dirs[i]);
        rows.push_back({readImage((d / dataset::viewExr("ref")).string()),
                        readImage((d / dataset::viewExr("src")).string()),
                        readImage((d / dataset::envmapExr(0)).string())});
    }
    writePng(contactSheet(rows, 120), (fs::path(out) / "contact_sheet.png").string());
}

}  // namespace

void writeDataset(const SynthOptions& o, const std::function<void(int, int, double)>& progress) {
    o.validate();
    PanoramaLibrary panoramas(o.hdriDir);
    panoramas.names();  // fails before anything is written if there are none
    fs::create_directories(o.out);
    nlohmann::json examples = nlohmann::json::array();
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::string> dirs;
    int owned = 0, done = 0;
    for (int i = 0; i < o.count; ++i) owned += o.shard.owns(std::size_t(i)) ? 1 : 0;
    for (int i = 0; i < o.count; ++i) {
        if (!o.shard.owns(std::size_t(i))) continue;
        const std::string id = exampleId(i);
        const std::string dir = (fs::path(o.out) / id).string();
        const uint64_t seed = exampleSeed(o.split, o.seed + i);
        ExampleSummary s;
        if (fs::exists(fs::path(dir) / dataset::kScene)) {  // complete from an earlier run
            s.id = id;
            s.seed = loadScene((fs::path(dir) / dataset::kScene).string()).seed;
        } else {
            s = writeExample(seed, dir, o, panoramas);
        }
        dirs.push_back(dir);
        examples.push_back({{"id", s.id},
                            {"example_seed", seed},
                            {"scene_seed", s.seed},
                            {"rejected_scenes", s.rejected},
                            {"seconds", s.seconds},
                            {"texels", s.texels}});
        if (progress)
            progress(
                ++done, owned,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (o.shard.active) {
        nlohmann::json record = {{"kind", "synth"},         {"shard", o.shard.index},
                                 {"shards", o.shard.count}, {"dataset", datasetHeader(o)},
                                 {"seconds", seconds},      {"examples", examples}};
        writeTextFile((fs::path(o.out) / o.shard.recordName()).string(), record.dump(1));
        return;
    }
    nlohmann::json manifest = datasetHeader(o);
    manifest["seconds"] = seconds;
    manifest["examples"] = examples;
    writeTextFile((fs::path(o.out) / "manifest.json").string(), manifest.dump(1));
    writeContactSheet(o.out, dirs);
}

int mergeDatasetShards(const std::string& dir) {
    const fs::path manifestPath = fs::path(dir) / "manifest.json";
    if (fs::exists(manifestPath))
        throw FileError(
            "'" + dir +
            "' is merged already (it holds manifest.json); remove manifest.json to merge again");
    const std::vector<nlohmann::json> records = readShardSet(dir, "synth", {"dataset"});
    nlohmann::json manifest = records.front()["dataset"];
    const int count = manifest.value("count", 0);
    std::vector<nlohmann::json> examples(std::size_t(std::max(count, 0)));
    double seconds = 0;
    for (const nlohmann::json& r : records) {
        seconds += r.value("seconds", 0.0);
        for (const nlohmann::json& e : r["examples"]) {
            const std::string id = e.value("id", "");
            const int index = std::atoi(id.c_str());
            if (id != exampleId(index) || index < 0 || index >= count ||
                !examples[std::size_t(index)].is_null())
                throw FileError("shard records in '" + dir + "' list example '" + id +
                                "' out of place");
            examples[std::size_t(index)] = e;
        }
    }
    std::vector<std::string> dirs;
    for (int i = 0; i < count; ++i) {
        if (examples[std::size_t(i)].is_null())
            throw FileError("shard records in '" + dir + "' lack example " + exampleId(i));
        const fs::path example = fs::path(dir) / exampleId(i);
        if (!fs::is_regular_file(example / dataset::kScene))
            throw FileError("example '" + example.string() +
                            "' listed by a shard record is missing or incomplete");
        dirs.push_back(example.string());
    }
    manifest["seconds"] = seconds;
    manifest["examples"] = examples;
    writeContactSheet(dir, dirs);
    writeTextFile(manifestPath.string(), manifest.dump(1));
    return count;
}

}  // namespace lh::synth
