// Time of `predict` (the network part: plane sweep, MPI network, resampling, completion, and
// the conversion to OpenVDB grids) for the `standard`, `wide`, `small` and `paper`
// configurations on the bundled 320x240 stereo pair, with the thread count libtorch is given.
// Each configuration is timed with random weights: its cost does not depend on their values.
// Target: the default under 5 s on 2 cores.
#include "core/camera.h"
#include "image/image_io.h"
#include "net/predictor.h"

#include <benchmark/benchmark.h>

#include <string>

namespace {

const std::string kPair = std::string(LIGHTHOUSE_SOURCE_DIR) + "/data/demo_pair/";

void predictWith(benchmark::State& state, const char* config) {
    lh::net::StereoPair pair{lh::readImage(kPair + "ref.png"), lh::readImage(kPair + "src.png"),
                             lh::loadCamerasFile(kPair + "cameras.json")};
    lh::net::PredictorOptions options;
    options.untrainedConfig = config;
    options.threads = int(state.range(0));
    const lh::net::Predictor predictor(options);
    for (auto _ : state) {
        const lh::net::Prediction p = predictor.predict(pair);
        benchmark::DoNotOptimize(p.seconds);
        state.counters["network_s"] = p.seconds;
    }
}

void BM_PredictStandard(benchmark::State& state) { predictWith(state, "standard"); }
void BM_PredictWide(benchmark::State& state) { predictWith(state, "wide"); }
void BM_PredictSmall(benchmark::State& state) { predictWith(state, "small"); }
void BM_PredictPaper(benchmark::State& state) { predictWith(state, "paper"); }

BENCHMARK(BM_PredictStandard)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_PredictWide)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_PredictSmall)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);
BENCHMARK(BM_PredictPaper)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
