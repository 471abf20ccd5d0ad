// Envmap rendering speed on the bundled example room (5 x 64^3), 240x120, at several
// points, with the default cell quadrature and with fixed steps. Run: build/bench/lighthouse_bench
// [--benchmark_filter=...] With LIGHTHOUSE_BENCH_VOLUME=FILE.vdb set, BM_EnvmapFile also times that
// volume at the random free-space points `lighthouse bench-envmap` uses (seed 1), per quadrature
// setting.
#include "render/envmap.h"
#include "render/free_space.h"
#include "vdb/example_volume.h"
#include "vdb/volume_io.h"

#include <benchmark/benchmark.h>

#include <cstdlib>

namespace {

const lh::RenderVolume& exampleRoom() {
    static const lh::RenderVolume volume(lh::makeExampleVolume(5, 64));
    return volume;
}

const lh::Vec3d kPoints[] = {lh::Vec3d(0, 0, 2), lh::Vec3d(0.2, 0.1, 0.4), lh::Vec3d(-1, 0.5, 4)};

// Arg: 0 = the default cell quadrature, else fixed steps of (arg / 100) voxels.
void BM_EnvmapExampleRoom(benchmark::State& state) {
    lh::EnvmapOptions options;
    if (state.range(0) > 0)
        options.march.cellNodes = 0, options.march.stepVoxels = double(state.range(0)) / 100.0;
    std::size_t i = 0;
    for (auto _ : state) {
        lh::ImageRGB env = lh::renderEnvmap(exampleRoom(), kPoints[i++ % 3], options);
        benchmark::DoNotOptimize(env.pixels.data());
    }
    state.SetLabel(options.march.cellNodes
                       ? "2 Gauss nodes/cell"
                       : "step " + std::to_string(options.march.stepVoxels) + " voxels");
    state.counters["envmaps/s"] =
        benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EnvmapExampleRoom)
    ->Arg(0)
    ->Arg(25)
    ->Arg(50)
    ->Arg(100)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Args: Gauss nodes per lattice cell (0: fixed 0.5-voxel steps), the cell quadrature's
// refinement bound (0: the default, 1; the coarse settings that compete with the paper's
// spheres in `bench-envmap` use 3 to 64) and whether rays start where they first meet the
// medium (1, the default; 0 to time the march from the origin: render/first_medium.h).
void BM_EnvmapFile(benchmark::State& state) {
    const char* path = std::getenv("LIGHTHOUSE_BENCH_VOLUME");
    if (!path) {
        state.SkipWithError("set LIGHTHOUSE_BENCH_VOLUME=FILE.vdb to time a volume file");
        return;
    }
    static const lh::RenderVolume volume(lh::loadVolume(path));
    static const std::vector<lh::Vec3d> points = lh::freeSpacePoints(volume, 8, 1);
    lh::EnvmapOptions options;
    options.march.cellNodes = int(state.range(0));
    if (state.range(1) > 0) options.march.cellRefineBound = double(state.range(1));
    options.startAtFirstMedium = state.range(2) != 0;
    std::size_t i = 0;
    for (auto _ : state) {
        lh::ImageRGB env = lh::renderEnvmap(volume, points[i++ % points.size()], options);
        benchmark::DoNotOptimize(env.pixels.data());
    }
    state.SetLabel(options.march.cellNodes
                       ? std::to_string(options.march.cellNodes) + " Gauss nodes/cell, bound " +
                             std::to_string(options.march.cellRefineBound) +
                             (options.startAtFirstMedium ? "" : ", from the origin")
                       : "step 0.5 voxels");
    state.counters["envmaps/s"] =
        benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EnvmapFile)
    ->Args({0, 0, 1})
    ->Args({1, 0, 1})
    ->Args({2, 0, 1})
    ->Args({3, 0, 1})
    ->Args({1, 3, 1})
    ->Args({1, 16, 1})
    ->Args({1, 64, 1})
    ->Args({2, 0, 0})
    ->Args({1, 3, 0})
    ->Args({1, 64, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_EnvmapReference(benchmark::State& state) {
    lh::EnvmapOptions options;
    options.march = lh::MarchOptions::reference();
    for (auto _ : state) {
        lh::ImageRGB env = lh::renderEnvmap(exampleRoom(), kPoints[0], options);
        benchmark::DoNotOptimize(env.pixels.data());
    }
}
BENCHMARK(BM_EnvmapReference)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

void BM_PrepareRenderVolume(benchmark::State& state) {
    const lh::LightingVolume volume = lh::makeExampleVolume(5, 64);
    for (auto _ : state) {
        lh::RenderVolume prepared(volume);
        benchmark::DoNotOptimize(prepared.levels.data());
    }
}
BENCHMARK(BM_PrepareRenderVolume)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
