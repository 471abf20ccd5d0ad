// Where one training step's time goes, per stage, forward and backward, with oneDNN's
// convolutions and with libtorch's native ones (net/step_profile.h):
//   lighthouse_train_step_bench [CONFIG] [REPEATS] [THREADS]   (default: standard 3 2)
// Prints a Markdown table.
#include "net/config.h"
#include "net/step_profile.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

int main(int argc, char** argv) {
    try {
        const std::string name = argc > 1 ? argv[1] : "standard";
        const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
        const int threads = argc > 3 ? std::atoi(argv[3]) : 2;
        if (repeats < 1 || threads < 1) {
            std::fprintf(stderr,
                         "usage: %s [standard|wide|paper|small] [REPEATS >= 1] [THREADS >= 1]\n",
                         argv[0]);
            return 2;
        }
        const lh::net::NetConfig config = lh::net::NetConfig::byName(name);
        const auto fast = lh::net::profileTrainingStep(config, repeats, threads, true);
        const auto native = lh::net::profileTrainingStep(config, repeats, threads, false);
        std::printf(
            "Training step of the `%s` configuration (%dx%d input, %d planes, %d x %d^3), %d "
            "threads, "
            "mean of %d steps, seconds:\n\n",
            name.c_str(), config.width, config.height, config.planes, config.levels,
            config.resolution, threads, repeats);
        std::printf(
            "| stage | forward | backward | forward, native conv | backward, native conv "
            "|\n|---|---|---|---|---|\n");
        double sums[4] = {0, 0, 0, 0};
        for (size_t i = 0; i < fast.size(); ++i) {
            std::printf("| %s | %.3f | %.3f | %.3f | %.3f |\n", fast[i].stage.c_str(),
                        fast[i].forwardSeconds, fast[i].backwardSeconds, native[i].forwardSeconds,
                        native[i].backwardSeconds);
            sums[0] += fast[i].forwardSeconds, sums[1] += fast[i].backwardSeconds;
            sums[2] += native[i].forwardSeconds, sums[3] += native[i].backwardSeconds;
        }
        std::printf("| **total** | %.3f | %.3f | %.3f | %.3f |\n", sums[0], sums[1], sums[2],
                    sums[3]);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
