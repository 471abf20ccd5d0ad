// Object insertion speed: a 640x480 view of the example room with one inserted
// object, lit per surface point through the 5 x 64^3 volume.
// Run: build/bench/lighthouse_insert_bench [--benchmark_filter=...]
#include "insert/insertion.h"
#include "render/view.h"
#include "vdb/example_volume.h"

#include <benchmark/benchmark.h>

namespace {

using namespace lh;

struct Setup {
    RenderVolume volume{makeExampleVolume(5, 64)};
    PinholeCamera camera;
    ImageRGB photo;
    Setup() {
        camera = exampleCameras().ref;
        camera.width = 640;
        camera.height = 480;
        camera.fx = camera.fy = camera.fx * 2;
        camera.cx = 320;
        camera.cy = 240;
        photo = renderView(volume, camera);
    }
};

const Setup& setup() {
    static const Setup s;
    return s;
}

// A sphere of radius 0.3 m on the table, about 1/8 of the frame.
void insertOne(benchmark::State& state, const char* material, int pixelSamples, int samples) {
    const std::vector<InsertedObject> objects{
        placeObject(builtinMesh("sphere"), Material::parse(material), Vec3d(0.0, 0.4, 3.0), 0.3)};
    InsertOptions options;
    options.pixelSamples = pixelSamples;
    options.samples = samples;
    const Setup& s = setup();  // built once, outside the timed loop
    for (auto _ : state) {
        ImageRGB out = insertObjects(s.volume, s.photo, s.camera, objects, options);
        benchmark::DoNotOptimize(out.pixels.data());
    }
}

void BM_Insert640x480_Mirror(benchmark::State& s) { insertOne(s, "mirror", 1, 1); }
void BM_Insert640x480_MirrorAntialiased(benchmark::State& s) { insertOne(s, "mirror", 2, 1); }
void BM_Insert640x480_Glossy64(benchmark::State& s) { insertOne(s, "glossy:0.3", 1, 64); }
void BM_Insert640x480_Diffuse64(benchmark::State& s) { insertOne(s, "diffuse:0.8,0.8,0.8", 1, 64); }
BENCHMARK(BM_Insert640x480_Mirror)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Insert640x480_MirrorAntialiased)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Insert640x480_Glossy64)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK(BM_Insert640x480_Diffuse64)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
