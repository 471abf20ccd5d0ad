#include "net/step_profile.h"

#include "net/device.h"
#include "net/fast_conv.h"
#include "net/lighthouse_net.h"
#include "net/losses.h"
#include "net/mpi_render.h"
#include "net/mpi_resample.h"
#include "net/psv.h"
#include "net/volume_render.h"

#include <chrono>
#include <cmath>
#include <functional>

namespace lh::net {

namespace {

double seconds(const std::function<void()>& work) {
    const auto start = std::chrono::steady_clock::now();
    work();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A textured wall 3 m away seen by a 10 cm stereo pair at the configuration's input size.
PairInputs planeInputs(const NetConfig& config) {
    PinholeCamera ref;
    ref.width = config.width;
    ref.height = config.height;
    ref.fx = ref.fy = 0.8 * config.width;
    ref.cx = config.width / 2.0;
    ref.cy = config.height / 2.0;
    PinholeCamera src = ref;
    src.position = Vec3d(0.1, 0.0, 0.0);
    ImageRGB a(ref.width, ref.height), b(ref.width, ref.height);
    for (int v = 0; v < ref.height; ++v)
        for (int u = 0; u < ref.width; ++u)
            for (int c = 0; c < 3; ++c) {
                a.at(u, v)[c] = float(0.5 + 0.4 * std::sin(0.3 * u + 0.2 * v + c));
                b.at(u, v)[c] = float(0.5 + 0.4 * std::sin(0.3 * (u + 2.7) + 0.2 * v + c));
            }
    return makePairInputs(a, b, ref, src, 1.0, 8.0, config, torch::Device(torch::kCPU));
}

}  // namespace

std::vector<StageTime> profileTrainingStep(const NetConfig& config, int repeats, int threads,
                                           bool oneDnn) {
    setTorchThreads(threads);
    setOneDnnConvolution(oneDnn);
    torch::manual_seed(0);
    LighthouseNet net(config);
    net->train();
    const PairInputs in = planeInputs(config);
    std::vector<StageTime> times = {{"plane sweep"},
                                    {"MPI network"},
                                    {"MPI view render + loss"},
                                    {"MPI -> cubes resampling"},
                                    {"completion networks"},
                                    {"envmap render + losses"},
                                    {"voxel loss"},
                                    {"optimiser step (Adam)"}};
    torch::optim::Adam adam(net->parameters(), torch::optim::AdamOptions(1e-4));
    for (int r = 0; r < repeats + 1; ++r) {  // the first round warms up and is not counted
        const bool counted = r > 0;
        const auto add = [&](int stage, double f, double b) {
            if (!counted) return;
            times[size_t(stage)].forwardSeconds += f / repeats;
            times[size_t(stage)].backwardSeconds += b / repeats;
        };
        torch::Tensor psv, mpi, loss;
        add(0, seconds([&] {
                psv = planeSweepVolume(in.refEncoded, in.srcEncoded, in.ref, in.src, in.depths);
            }),
            0);
        double f = seconds(
            [&] { mpi = net->predictMpi(psv, in.refLinear, net->logColourAnchor(in.refLinear)); });
        add(1, f, seconds([&] { mpi.sum().backward(); }));

        const auto mpiLeaf = mpi.detach().requires_grad_(true);
        f = seconds([&] {
            loss = imageLoss(renderMpiView(mpiLeaf, in.depths, in.ref, in.ref), in.refLinear);
        });
        add(2, f, seconds([&] { loss.backward(); }));

        std::vector<torch::Tensor> cubes;
        f = seconds([&] {
            for (int k = 0; k < in.layout.levels; ++k)
                cubes.push_back(resampleMpiToLevel(mpiLeaf, in.depths, in.ref, in.layout, k,
                                                   config.hdr ? kMaxMpiRadiance : 1.0));
        });
        add(3, f, seconds([&] {
                torch::Tensor total = torch::zeros({});
                for (const auto& c : cubes) total = total + c.sum();
                total.backward();
            }));

        std::vector<torch::Tensor> inputs, completed;
        for (const auto& c : cubes) inputs.push_back(c.detach());
        f = seconds([&] {
            completed = net->complete(inputs, in.layout, net->logColourAnchor(in.refLinear));
        });
        add(4, f, seconds([&] {
                torch::Tensor total = torch::zeros({});
                for (const auto& c : completed) total = total + c.sum();
                total.backward();
            }));

        std::vector<torch::Tensor> leaves;
        for (const auto& c : completed) leaves.push_back(c.detach().requires_grad_(true));
        const auto target = torch::full({1, 3, config.trainEnvHeight, config.trainEnvWidth}, 0.3);
        f = seconds([&] {
            const auto env =
                renderEnvmapTorch(leaves, in.layout, Vec3d(0.1, 0.0, 1.5), config.trainEnvWidth,
                                  config.trainEnvHeight, config.samplesPerLevel);
            loss = imageLoss(env, target) + hdrImageLoss(env, target);
        });
        add(5, f, seconds([&] { loss.backward(); }));

        std::vector<torch::Tensor> zeros;
        for (const auto& c : leaves) zeros.push_back(torch::zeros_like(c));
        f = seconds([&] { loss = voxelLoss(leaves, zeros); });
        add(6, f, seconds([&] { loss.backward(); }));
        add(7, seconds([&] { adam.step(); }), 0);
        adam.zero_grad();
    }
    setOneDnnConvolution(true);
    return times;
}

}  // namespace lh::net
