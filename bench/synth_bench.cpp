// Synthetic data generation speed: Embree ray casting, the light bake, and whole examples at
// the `small` network configuration's sizes (views 160x120, envmaps 120x60).
// Run: build/bench/lighthouse_synth_bench [--benchmark_filter=...]
#include "core/random.h"
#include "synth/dataset.h"
#include "synth/scene_generator.h"

#include <benchmark/benchmark.h>

#include <filesystem>

namespace {

using namespace lh;
using namespace lh::synth;

PanoramaLibrary& panoramas() {
    static PanoramaLibrary library(LIGHTHOUSE_HDRI_DIR);
    return library;
}

void BM_RayCast(benchmark::State& state) {
    const GeneratedScene gen = generateScene(42, panoramas().names(), 160, 120);
    const RayTracer tracer(gen.scene);
    Random rng(1);
    std::size_t hits = 0;
    for (auto _ : state) {
        const double z = 1 - 2 * rng.uniform(), phi = 2 * M_PI * rng.uniform(),
                     r = std::sqrt(1 - z * z);
        hits += tracer.intersect(Vec3d(0.0), Vec3d(r * std::cos(phi), r * std::sin(phi), z)).hit;
    }
    benchmark::DoNotOptimize(hits);
    state.counters["rays/s"] =
        benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
    state.SetLabel(std::to_string(tracer.triangleCount()) + " triangles, one thread");
}
BENCHMARK(BM_RayCast);

void BM_BakeRoom(benchmark::State& state) {
    const GeneratedScene gen = generateScene(42, panoramas().names(), 160, 120);
    for (const auto& w : gen.scene.windows) panoramas().get(w.panorama);
    const RayTracer tracer(gen.scene);
    for (auto _ : state) {
        RadianceField field(gen.scene, tracer, panoramas());
        benchmark::DoNotOptimize(field.texelCount());
    }
}
BENCHMARK(BM_BakeRoom)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SmallExample(benchmark::State& state) {
    SynthOptions o;
    o.width = 160;
    o.height = 120;
    o.envWidth = 120;
    o.envHeight = 60;
    o.hdriDir = LIGHTHOUSE_HDRI_DIR;
    const auto dir = std::filesystem::temp_directory_path() / "lh_synth_bench";
    std::filesystem::create_directories(dir);
    uint64_t index = 0;
    for (auto _ : state)
        writeExample(exampleSeed("train", index++), (dir / "example").string(), o, panoramas());
    state.counters["examples/hour"] =
        benchmark::Counter(3600.0 * state.iterations(), benchmark::Counter::kIsRate);
    std::filesystem::remove_all(dir);
}
BENCHMARK(BM_SmallExample)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(20);

}  // namespace

BENCHMARK_MAIN();
