#include "net/lamp_cell_pretraining.h"

#include "core/dataset_files.h"
#include "core/errors.h"
#include "image/image_io.h"
#include "net/config.h"
#include "net/lighthouse_net.h"
#include "net/losses.h"
#include "synth/scene_json.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <numeric>
#include <random>

namespace lh::net {

namespace fs = std::filesystem;

namespace {

constexpr double kUniformShare = 1e-3;  // mixed into the starting distribution: no cell impossible

// KL(target || softmax(logits)) per row, nats: [N].
torch::Tensor divergence(const torch::Tensor& logits, const torch::Tensor& target) {
    return cellDivergence(target, torch::log_softmax(logits, 1));
}

LampCellScores scoreLogits(const std::function<torch::Tensor(const LampCellExample&)>& logitsOf,
                           const std::vector<LampCellExample>& examples) {
    LampCellScores s;
    if (examples.empty()) return s;
    for (const auto& e : examples) {
        const auto logits = logitsOf(e).reshape({1, -1});
        s.divergence += divergence(logits, e.cells.unsqueeze(0)).item<double>();
        s.peakHit += e.cells[logits.argmax().item<int64_t>()].item<double>() > 0 ? 1.0 : 0.0;
    }
    s.divergence /= double(examples.size());
    s.peakHit /= double(examples.size());
    return s;
}

}  // namespace

torch::Tensor lampCellTarget(const torch::Tensor& lamps, double far, int cellsPerSide,
                             bool mirrored) {
    if (!lamps.defined() || lamps.size(0) == 0)
        throw InputError("a lamp-cell target needs at least one lamp");
    const double side = 2.0 * std::min(far, 20.0), cell = side / cellsPerSide;
    const auto cpu = lamps.to(torch::kCPU, torch::kFloat64).contiguous();
    auto target = torch::zeros({int64_t(cellsPerSide) * cellsPerSide * cellsPerSide});
    const int64_t m = cpu.size(0);
    for (int64_t i = 0; i < m; ++i) {
        int index[3];
        for (int a = 0; a < 3; ++a) {
            const double u = std::floor((cpu[i][a].item<double>() + side / 2) / cell);
            index[a] = int(std::clamp(u, 0.0, double(cellsPerSide - 1)));
        }
        if (mirrored) index[0] = cellsPerSide - 1 - index[0];
        const int64_t flat =
            (int64_t(index[2]) * cellsPerSide + index[1]) * cellsPerSide + index[0];
        target[flat] += 1.0 / double(m);
    }
    return target;
}

torch::Tensor lampCentresOfScene(const std::string& sceneJson) {
    std::vector<float> centres;
    for (const synth::Primitive& prim : synth::loadScene(sceneJson).primitives)
        if (prim.isEmitter())
            for (double v : {prim.centre.x(), prim.centre.y(), prim.centre.z()})
                centres.push_back(float(v));
    if (centres.empty()) return {};
    return torch::tensor(centres).reshape({-1, 3});
}

torch::Tensor lampsOutsideView(const torch::Tensor& centres, const PinholeCamera& camera) {
    if (!centres.defined()) return {};
    const auto cpu = centres.to(torch::kCPU, torch::kFloat64).contiguous();
    std::vector<int64_t> outside;
    for (int64_t i = 0; i < cpu.size(0); ++i) {
        const Vec3d world{cpu[i][0].item<double>(), cpu[i][1].item<double>(),
                          cpu[i][2].item<double>()};
        if (!camera.projectIntoImage(world)) outside.push_back(i);
    }
    if (outside.empty()) return {};
    return centres.index_select(0, torch::tensor(outside).to(centres.device()));
}

LampCellExample loadLampCellExample(const std::string& directory, const NetConfig& config, bool& ok,
                                    bool unseenOnly) {
    const fs::path dir(directory);
    LampCellExample e;
    ok = false;
    if (!fs::is_regular_file(dir / dataset::kScene)) return e;
    torch::Tensor lamps = lampCentresOfScene((dir / dataset::kScene).string());
    if (!lamps.defined()) return e;
    const CamerasFile cameras = loadCamerasFile((dir / dataset::kCameras).string());
    if (!cameras.far) throw FileError((dir / dataset::kCameras).string() + ": no far depth");
    if (unseenOnly) lamps = lampsOutsideView(lamps, cameras.ref);
    if (!lamps.defined()) return e;
    // As the pipeline gives it to the head (LighthouseNetImpl::run): the photo before its clip
    // at 1 where the model reads that and the example has it, else the saved photo.
    const bool unclipped =
        config.emitterPhotoUnclipped && fs::is_regular_file(dir / dataset::viewExr("ref"));
    const std::string view = unclipped ? dataset::viewExr("ref") : dataset::viewPng("ref");
    e.photo = photoRadianceTensor(readImage((dir / view).string()), config.width, config.height);
    e.cells = lampCellTarget(lamps, *cameras.far, kEmitterCellsPerSide);
    e.mirroredCells = lampCellTarget(lamps, *cameras.far, kEmitterCellsPerSide, /*mirrored=*/true);
    ok = true;
    return e;
}

LampCellScores scoreLampCells(EmitterHead& head, const std::vector<LampCellExample>& examples) {
    torch::NoGradGuard noGrad;
    const bool wasTraining = head->is_training();
    head->eval();
    const auto device = head->parameters().front().device();
    const LampCellScores s = scoreLogits(
        [&](const LampCellExample& e) {
            return head->photoCellLogits(e.photo.to(device)).to(torch::kCPU);
        },
        examples);
    head->train(wasTraining);
    return s;
}

LampCellScores scoreLampCells(const torch::Tensor& distribution,
                              const std::vector<LampCellExample>& examples) {
    const auto logits = distribution.log();
    return scoreLogits([&](const LampCellExample&) { return logits; }, examples);
}

LampCellScores pretrainLampCells(EmitterHead& head, const std::vector<LampCellExample>& training,
                                 const std::vector<LampCellExample>& heldOut,
                                 const LampCellPretraining& o, std::ostream& progress) {
    if (training.empty()) throw InputError("lamp-cell pretraining needs training photos");
    const auto device = head->parameters().front().device();
    // The training photos' own distribution of lamp cells: the best answer without the photo,
    // where the classifier starts.
    auto prior = torch::zeros_like(training.front().cells);
    for (const auto& e : training) prior += e.cells + e.mirroredCells;
    prior = (1 - kUniformShare) * prior / prior.sum() + kUniformShare / double(prior.numel());
    {
        torch::NoGradGuard noGrad;
        head->photoCellsOutput()->bias.copy_(prior.log().to(device));
    }
    const LampCellScores blind = scoreLampCells(prior, heldOut);
    progress << "train: lamp cells from photos alone, " << training.size() << " photos (and "
             << "their mirror images), " << heldOut.size() << " held out; the training photos' "
             << "own distribution scores " << std::fixed << std::setprecision(3) << blind.divergence
             << " nats, peak on a lamp " << std::setprecision(2) << blind.peakHit << " there\n";

    std::vector<torch::Tensor> parameters = head->photoEncoder->parameters();
    for (const auto& p : head->photoCells->parameters()) parameters.push_back(p);
    torch::optim::Adam adam(parameters,
                            torch::optim::AdamOptions(o.learningRate).weight_decay(o.weightDecay));
    std::mt19937_64 rng(o.seed);
    std::vector<size_t> order(training.size());
    std::iota(order.begin(), order.end(), size_t(0));
    // The epoch that scores best on the held-out photos is kept (all of them without any).
    LampCellScores best = scoreLampCells(head, heldOut);
    int bestEpoch = 0;
    std::vector<torch::Tensor> bestWeights;
    const auto keepBest = [&] {
        torch::NoGradGuard noGrad;
        bestWeights.clear();
        for (const auto& p : parameters) bestWeights.push_back(p.detach().clone());
    };
    keepBest();
    const bool wasTraining = head->is_training();
    for (int epoch = 1; epoch <= o.epochs; ++epoch) {
        head->train();
        std::shuffle(order.begin(), order.end(), rng);
        double sum = 0;
        int batches = 0;
        for (size_t b = 0; b < order.size(); b += size_t(o.batch)) {
            std::vector<torch::Tensor> photos, targets;
            for (size_t j = b; j < std::min(order.size(), b + size_t(o.batch)); ++j) {
                const LampCellExample& e = training[order[j]];
                const bool mirror = (rng() & 1u) != 0;
                photos.push_back(mirror ? e.photo.flip({3}) : e.photo);
                targets.push_back(mirror ? e.mirroredCells : e.cells);
            }
            const auto logits = head->photoCellLogits(torch::cat(photos).to(device));
            const auto loss = divergence(logits, torch::stack(targets).to(device)).mean();
            adam.zero_grad();
            loss.backward();
            adam.step();
            sum += loss.item<double>();
            ++batches;
        }
        const LampCellScores now = scoreLampCells(head, heldOut);
        progress << "train: lamp cells, epoch " << epoch << "/" << o.epochs << ": training "
                 << std::setprecision(3) << sum / batches << " nats; held out " << now.divergence
                 << " nats, peak on a lamp " << std::setprecision(2) << now.peakHit << "\n";
        if (heldOut.empty() || now.divergence < best.divergence) {
            best = now;
            bestEpoch = epoch;
            keepBest();
        }
    }
    {
        torch::NoGradGuard noGrad;
        for (size_t i = 0; i < parameters.size(); ++i) parameters[i].copy_(bestWeights[i]);
    }
    head->train(wasTraining);
    progress << "train: lamp cells: kept epoch " << bestEpoch << " (held out "
             << std::setprecision(3) << best.divergence << " nats, peak on a lamp "
             << std::setprecision(2) << best.peakHit << ")\n";
    return best;
}

}  // namespace lh::net
