// Microbenchmarks of the renderer's hot paths: trilinear sampling, segment
// integration along one ray, and level lookup (finest-wins partition of a ray). Stable case
// names; run: build/bench/lighthouse_hotpath_bench [--benchmark_filter=Sample]
// Single-threaded: each case times one call path, not the TBB envmap loop.
#include "render/ray_marcher.h"
#include "vdb/example_volume.h"

#include <benchmark/benchmark.h>

#include <random>

namespace {

const lh::RenderVolume& exampleRoom() {
    static const lh::RenderVolume volume(lh::makeExampleVolume(5, 64));
    return volume;
}

// Random points in continuous index space of level `k`'s domain, fixed seed.
std::vector<lh::Vec3d> indexPoints(const lh::RenderLevel& level, int n) {
    std::mt19937 rng(7);
    std::vector<lh::Vec3d> points;
    for (int i = 0; i < n; ++i) {
        lh::Vec3d q;
        for (int a = 0; a < 3; ++a)
            q[a] =
                std::uniform_real_distribution<double>(level.domainLo[a], level.domainHi[a])(rng);
        points.push_back(q);
    }
    return points;
}

std::vector<lh::Vec3d> unitDirections(int n) {
    std::mt19937 rng(11);
    std::normal_distribution<double> g;
    std::vector<lh::Vec3d> dirs;
    for (int i = 0; i < n; ++i) dirs.push_back(lh::Vec3d(g(rng), g(rng), g(rng)).unit());
    return dirs;
}

// RenderLevel::sample: brick table lookup + trilinear lookup of sigma and emission.
void BM_SampleLevel(benchmark::State& state) {
    const lh::RenderLevel& level = exampleRoom().levels[1];
    const auto points = indexPoints(level, 4096);
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(level.sample(points[i++ & 4095]));
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SampleLevel);

// RenderLevel::sampleLattice: the marcher's inner lookup inside one known brick.
void BM_SampleLattice(benchmark::State& state) {
    const lh::RenderLevel& level = exampleRoom().levels[1];
    const float* brick = level.brickPointer(0);
    std::mt19937 rng(3);
    std::vector<float> u(3 * 4096);
    for (float& x : u) x = std::uniform_real_distribution<float>(0.f, 8.f)(rng);
    std::size_t i = 0;
    for (auto _ : state) {
        const float* p = &u[3 * (i++ & 4095)];
        benchmark::DoNotOptimize(lh::RenderLevel::sampleLattice(brick, p[0], p[1], p[2]));
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SampleLattice);

// RenderVolume::sampleWorld: finest-level lookup of a world point, then a sample.
void BM_SampleWorld(benchmark::State& state) {
    const lh::RenderVolume& volume = exampleRoom();
    const auto& level = volume.levels[1];
    std::vector<lh::Vec3d> world;
    for (const auto& q : indexPoints(level, 4096))
        world.push_back(level.indexToWorld * (q - level.indexOffset));
    std::size_t i = 0;
    for (auto _ : state) benchmark::DoNotOptimize(volume.sampleWorld(world[i++ & 4095]));
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SampleWorld);

// Level lookup: the finest-wins partition of a ray into per-level pieces.
void BM_PartitionRay(benchmark::State& state) {
    const lh::RenderVolume& volume = exampleRoom();
    const auto dirs = unitDirections(4096);
    lh::Piece pieces[lh::RenderVolume::kMaxPieces];
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(
            volume.partitionRay(lh::Vec3d(0.1, 0.2, 2.0), dirs[i++ & 4095], pieces));
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PartitionRay);

// Segment integration: whole rays from a point in the room, with the default cell quadrature
// (first argument 0) or fixed steps of (first argument / 100) voxels, with and without
// empty-space skipping; items = rays.
void BM_MarchRay(benchmark::State& state) {
    const lh::RenderVolume& volume = exampleRoom();
    const auto dirs = unitDirections(4096);
    lh::MarchOptions o;
    if (state.range(0) > 0) o.cellNodes = 0, o.stepVoxels = double(state.range(0)) / 100.0;
    o.skipEmptySpace = state.range(1) != 0;
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(
            lh::marchRay(volume, lh::Vec3d(0.1, 0.2, 2.0), dirs[i++ & 4095], o));
    }
    state.SetItemsProcessed(state.iterations());
    state.SetLabel((o.cellNodes ? std::to_string(o.cellNodes) + " Gauss nodes/cell"
                                : "step " + std::to_string(o.stepVoxels)) +
                   (o.skipEmptySpace ? ", skipping" : ", no skipping"));
}
BENCHMARK(BM_MarchRay)->Args({0, 1})->Args({50, 1})->Args({100, 1})->Args({50, 0});

// Segment integration through a homogeneous thick medium: the sub-stepping path.
void BM_MarchRayThickMedium(benchmark::State& state) {
    static const lh::RenderVolume cube = [] {
        lh::LightingVolume v = lh::LightingVolume::fromLayout(lh::VolumeLayout{4.0, 1, 64});
        v.fillLevel(0, [](const lh::Vec3d&) {
            return lh::MediumSample{50.f, openvdb::Vec3s(1.f)};
        });
        return lh::RenderVolume(v);
    }();
    const auto dirs = unitDirections(4096);
    std::size_t i = 0;
    for (auto _ : state)
        benchmark::DoNotOptimize(
            lh::marchRay(cube, lh::Vec3d(0.0), dirs[i++ & 4095], lh::MarchOptions{}));
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MarchRayThickMedium);

}  // namespace

BENCHMARK_MAIN();
