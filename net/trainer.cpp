#include "net/trainer.h"

#include "core/atomic_file.h"
#include "core/dataset_files.h"
#include "core/errors.h"
#include "core/random.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "image/photo_clipping.h"
#include "image/resample.h"
#include "net/augment.h"
#include "net/curve_plot.h"
#include "net/device.h"
#include "net/distributed.h"
#include "net/emitter_light.h"
#include "net/exposure_filter.h"
#include "net/highlight_gain.h"
#include "net/lamp_cell_pretraining.h"
#include "net/lighthouse_net.h"
#include "net/losses.h"
#include "net/mpi_render.h"
#include "net/oracle_targets.h"
#include "net/predictor.h"
#include "net/tensor_image.h"
#include "net/training_data.h"
#include "net/vgg_loss.h"
#include "net/volume_render.h"
#include "net/weight_average.h"
#include "net/widen.h"
#include "synth/scene_json.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace fs = std::filesystem;

namespace lh::net {

void TrainOptions::validate() const {
    if (iterations < 1) throw InputError("--iterations must be at least 1");
    if (!(learningRate > 0 && learningRate < 1)) throw InputError("--lr must be in (0, 1)");
    if (validateEvery < 1 || checkpointEvery < 1 || logEvery < 1)
        throw InputError("--validate-every, --checkpoint-every and --log-every must be at least 1");
    if (validationScenes < 1) throw InputError("--validation-scenes must be at least 1");
    if (supervision != "direct" && supervision != "paper")
        throw InputError("--supervision must be 'direct' or 'paper', got '" + supervision + "'");
    if (stopAfter < 0) throw InputError("--stop-after must be at least 0");
    if (!(maxClipped >= 0.0 && maxClipped <= 1.0))
        throw InputError("--max-clipped must be a fraction in [0, 1]");
    if (!(maxPhotoClipped >= 0.0 && maxPhotoClipped <= 1.0))
        throw InputError("--max-photo-clipped must be a fraction in [0, 1]");
    if (batch < 1 || batch > 4096) throw InputError("--batch must be in [1, 4096]");
    if (!(averageDecay >= 0 && averageDecay < 1))
        throw InputError("--average-decay must be in [0, 1)");
    if (!(irradianceWeight >= 0 && irradianceWeight <= 100))
        throw InputError("--irradiance-weight must be in [0, 100]");
    if (!(irradianceFocus >= 0 && irradianceFocus <= 4))
        throw InputError("--irradiance-focus must be in [0, 4]");
    if (!(envmapSquaredWeight >= 0 && envmapSquaredWeight <= 100))
        throw InputError("--envmap-mse-weight must be in [0, 100]");
    if (!(highlightWeight >= 0 && highlightWeight <= 100))
        throw InputError("--highlight-weight must be in [0, 100]");
    if (!(coarseEnvmapWeight >= 0 && coarseEnvmapWeight <= 100))
        throw InputError("--coarse-envmap-weight must be in [0, 100]");
    if (!(coarseEnvmapBlock >= 1 && coarseEnvmapBlock <= 60))
        throw InputError("--coarse-envmap-block must be in [1, 60] pixels");
    if (!(viewHdrWeight >= 0 && viewHdrWeight <= 100))
        throw InputError("--view-hdr-weight must be in [0, 100]");
    if (!(pruneAlpha >= 0 && pruneAlpha < 1)) throw InputError("--prune-alpha must be in [0, 1)");
    validateHighlightGain(highlightGain);
    if (!(alphaBinaryWeight >= 0 && alphaBinaryWeight <= 1000))
        throw InputError("--alpha-binary-weight must be in [0, 1000]");
    if (!(emitterPositionWeight >= 0 && emitterPositionWeight <= 1000))
        throw InputError("--emitter-position-weight must be in [0, 1000]");
    if (!(emitterCellWeight >= 0 && emitterCellWeight <= 1000))
        throw InputError("--emitter-cell-weight must be in [0, 1000]");
    if (!(emitterLightWeight >= 0 && emitterLightWeight <= 1000))
        throw InputError("--emitter-light-weight must be in [0, 1000]");
    if (pretrainLampCellEpochs < 0 || pretrainLampCellEpochs > 1000)
        throw InputError("--pretrain-lamp-cells must be in [0, 1000] epochs");
    if (lampCellsUnseenOnly && emitterCellWeight == 0 && pretrainLampCellEpochs == 0)
        throw InputError(
            "--lamp-cells-unseen changes the lamp cells of --emitter-cell-weight and "
            "--pretrain-lamp-cells: give one of them too");
    if (!(closureWeight >= 0 && closureWeight <= 100))
        throw InputError("--closure-weight must be in [0, 100]");
    if (!(directAdversarialWeight >= 0 && directAdversarialWeight <= 10))
        throw InputError("--direct-adversarial-weight must be in [0, 10]");
    if (adversarialInput != "srgb" && adversarialInput != "log")
        throw InputError("--adversarial-input must be 'srgb' or 'log', got '" + adversarialInput +
                         "'");
    if (directAdversarialWeight > 0 && supervision != "direct")
        throw InputError(
            "--direct-adversarial-weight needs --supervision direct (the paper's "
            "supervision has its own adversarial stage)");
    if (batch % distributed.worldSize != 0)
        throw InputError(
            "--batch " + std::to_string(batch) + " must be a multiple of the world size " +
            std::to_string(distributed.worldSize) + " (each rank takes an equal slice)");
    (configOverride ? *configOverride : NetConfig::byName(config)).validate();
}

namespace {

constexpr double kStage2Start = 0.25, kStage3Start = 0.9, kLowLearningRateStart = 0.8;
constexpr double kAdversarialWeight = 0.1, kGradientClipNorm = 5.0;

constexpr double kSparsityWeight = 0.05;  // paper supervision only

struct LogRow {
    int iteration = 0, stage = 1;
    double total = 0, view = 0, envmap = 0, adversarial = 0, discriminator = 0;
    double learningRate = 0, itPerSecond = 0;
    double valPsnr = NAN, valAngular = NAN;
    double voxel = 0, depth = 0;
    double emitterCells = 0;  // emitterCellLoss, unweighted (nats); not in the CSV log
    double emitterLight = 0;  // emitterLightLoss, unweighted; not in the CSV log
    double secondsData = 0, secondsForward = 0, secondsBackward = 0;  // per iteration, mean
    double secondsAllReduce = 0;  // per iteration, mean: data-parallel communication
};

// Loss terms summed per iteration: total, view, envmap, adversarial, discriminator, voxel,
// depth, emitter cells, emitter light.
constexpr int kLossTerms = 9;

constexpr const char* kLogHeader =
    "iteration,stage,loss_total,loss_view,loss_envmap,loss_adversarial,loss_discriminator,lr,"
    "it_per_s,val_psnr_db,val_angular_deg,loss_voxel,loss_depth,s_data,s_forward,s_backward,"
    "s_allreduce";

// Direct supervision runs every network from the start, with the adversarial term (stage 3)
// from the start too where it has a weight.
int stageAt(int iteration, int total, bool direct, bool directAdversarial) {
    if (direct) return directAdversarial ? 3 : 2;
    if (iteration >= int(kStage3Start * total)) return 3;
    if (iteration >= int(kStage2Start * total)) return 2;
    return 1;
}

struct TrainingState {
    LighthouseNet net{nullptr};
    LighthouseNet average{nullptr};  // the moving average of net's weights: the model written
    PatchDiscriminator discriminator{nullptr};
    std::unique_ptr<torch::optim::Adam> optimizer, discriminatorOptimizer;
    // The optimiser's parameter groups run at these multiples of the learning rate.
    std::vector<double> learningRateScales{1.0};
    int iteration = 0;
    std::vector<LogRow> log;
};

// An emitter head (net/emitter_head.h) starts from nothing inside a model being fine-tuned at a
// small learning rate, where Adam would move its opacity logit (-4 at the start) by about that
// rate per step: it would stay dark for the whole run. It trains this many times faster.
constexpr double kEmitterHeadLearningRateScale = 100.0;

// A pretrained photo classifier (train --pretrain-lamp-cells) and its encoder go on at the
// rate they were pretrained at (1e-3 at the usual 1e-4), not the fresh head's: at 100 times the
// rate, 25 steps undid the pretraining (the logged divergence 3.61 nats, against 3.00 on the
// held-out photos just before).
constexpr double kPretrainedPhotoLearningRateScale = 10.0;

// The parameters of `all` that are not among `excluded` (the same tensors, not equal values).
std::vector<torch::Tensor> parametersNotIn(const std::vector<torch::Tensor>& all,
                                           const std::vector<torch::Tensor>& excluded) {
    std::vector<torch::Tensor> out;
    for (const auto& p : all) {
        const bool in = std::any_of(excluded.begin(), excluded.end(), [&](const torch::Tensor& e) {
            return e.unsafeGetTensorImpl() == p.unsafeGetTensorImpl();
        });
        if (!in) out.push_back(p);
    }
    return out;
}

// Adam over the network's parameters: one group, or two with an emitter head (its own rate),
// or three when its photo classifier was pretrained (`pretrainedPhoto`; the classifier and the
// photo encoder at their own rate).
void makeNetOptimizer(TrainingState& s, double lr, bool pretrainedPhoto) {
    if (!s.net->emitterHead) {
        s.optimizer = std::make_unique<torch::optim::Adam>(s.net->parameters(),
                                                           torch::optim::AdamOptions(lr));
        s.learningRateScales = {1.0};
        return;
    }
    const auto all = s.net->parameters();
    auto head = s.net->emitterHead->parameters();
    std::vector<torch::optim::OptimizerParamGroup> groups;
    groups.emplace_back(parametersNotIn(all, head),
                        std::make_unique<torch::optim::AdamOptions>(lr));
    s.learningRateScales = {1.0, kEmitterHeadLearningRateScale};
    if (pretrainedPhoto) {
        auto pretrained = s.net->emitterHead->photoEncoder->parameters();
        for (const auto& p : s.net->emitterHead->photoCells->parameters()) pretrained.push_back(p);
        head = parametersNotIn(head, pretrained);
        groups.emplace_back(pretrained, std::make_unique<torch::optim::AdamOptions>(
                                            lr * kPretrainedPhotoLearningRateScale));
        s.learningRateScales = {1.0, kPretrainedPhotoLearningRateScale,
                                kEmitterHeadLearningRateScale};
    }
    groups.emplace_back(
        head, std::make_unique<torch::optim::AdamOptions>(lr * kEmitterHeadLearningRateScale));
    s.optimizer = std::make_unique<torch::optim::Adam>(groups, torch::optim::AdamOptions(lr));
}

// `train --pretrain-lamp-cells`: the emitter head's photo classifier trained on the training
// photos alone (net/lamp_cell_pretraining.h), scored on the held-out ones.
void pretrainPhotoClassifier(const TrainOptions& o, TrainingState& s,
                             const std::vector<std::string>& trainDirs,
                             const std::vector<std::string>& heldOutDirs, std::ostream& progress) {
    const auto load = [&](const std::vector<std::string>& dirs) {
        std::vector<LampCellExample> examples;
        for (const auto& dir : dirs) {
            bool ok = false;
            LampCellExample e = loadLampCellExample(dir, s.net->config, ok, o.lampCellsUnseenOnly);
            if (ok) examples.push_back(std::move(e));
        }
        return examples;
    };
    const std::vector<LampCellExample> training = load(trainDirs), heldOut = load(heldOutDirs);
    if (training.empty())
        throw InputError(std::string("--pretrain-lamp-cells needs scenes with lamps in "
                                     "scene.json") +
                         (o.lampCellsUnseenOnly ? " that the photo does not show" : "") + "; '" +
                         o.data + "' has none");
    LampCellPretraining options;
    options.epochs = o.pretrainLampCellEpochs;
    options.seed = o.seed;
    pretrainLampCells(s.net->emitterHead, training, heldOut, options, progress);
}

void setLearningRate(torch::optim::Adam& optimizer, double lr,
                     const std::vector<double>& scales = {1.0}) {
    auto& groups = optimizer.param_groups();
    for (size_t i = 0; i < groups.size(); ++i)
        static_cast<torch::optim::AdamOptions&>(groups[i].options())
            .lr(lr * scales[std::min(i, scales.size() - 1)]);
}

void saveCheckpoint(const TrainOptions& o, TrainingState& s) {
    torch::serialize::OutputArchive archive, net, average, disc, opt, discOpt;
    s.net->save(net);
    s.average->save(average);
    archive.write("average", average);
    s.discriminator->save(disc);
    s.optimizer->save(opt);
    s.discriminatorOptimizer->save(discOpt);
    archive.write("net", net);
    archive.write("discriminator", disc);
    archive.write("optimizer", opt);
    archive.write("discriminator_optimizer", discOpt);
    archive.write("iteration", c10::IValue(int64_t(s.iteration)));
    archive.write("config", c10::IValue(s.net->config.toJson()));
    const fs::path target(o.checkpointPath());
    if (!target.parent_path().empty()) fs::create_directories(target.parent_path());
    // Under a temporary name, then renamed: a kill at any moment leaves the last complete
    // checkpoint, and the next run removes the temporary (core/atomic_file.h).
    AtomicOutput out(o.checkpointPath());
    archive.save_to(out.tempPath());
    out.commit();
    saveModel(s.average, o.out, o.halfModel);
}

bool loadCheckpoint(const TrainOptions& o, TrainingState& s) {
    if (!o.resume || !fs::is_regular_file(o.checkpointPath())) return false;
    torch::serialize::InputArchive archive, net, disc, opt, discOpt;
    try {
        archive.load_from(o.checkpointPath());
        c10::IValue config, iteration;
        archive.read("config", config);
        if (NetConfig::fromJson(config.toStringRef(), o.checkpointPath()).toJson() !=
            s.net->config.toJson())
            throw FileError(
                "checkpoint '" + o.checkpointPath() +
                "' was trained with another configuration; delete it or pick another -o");
        archive.read("net", net);
        archive.read("discriminator", disc);
        archive.read("optimizer", opt);
        archive.read("discriminator_optimizer", discOpt);
        archive.read("iteration", iteration);
        s.net->load(net);
        // A checkpoint from before the average was kept starts it at its weights.
        torch::serialize::InputArchive average;
        if (archive.try_read("average", average))
            s.average->load(average);
        else
            copyWeights(s.average, s.net);
        s.discriminator->load(disc);
        s.optimizer->load(opt);
        s.discriminatorOptimizer->load(discOpt);
        s.iteration = int(iteration.toInt());
    } catch (const c10::Error& e) {
        throw FileError("checkpoint '" + o.checkpointPath() + "' is unreadable (" +
                        std::string(e.what_without_backtrace()).substr(0, 200) +
                        "); delete it to start afresh");
    }
    return true;
}

std::vector<CurveSeries> nonEmpty(std::vector<CurveSeries> series) {
    series.erase(std::remove_if(series.begin(), series.end(),
                                [](const CurveSeries& c) { return c.x.empty(); }),
                 series.end());
    return series;
}

// The log rows of an earlier run of this training (its CSV), up to `lastIteration`, so that a
// resumed run keeps whole curves. Columns are read by name: a CSV from before a column was
// added leaves it at its default.
std::vector<LogRow> readLog(const std::string& path, int lastIteration) {
    std::vector<LogRow> rows;
    std::ifstream csv(path);
    std::string line;
    if (!std::getline(csv, line)) return rows;
    std::vector<std::string> names;
    {
        std::istringstream header(line);
        for (std::string name; std::getline(header, name, ',');) names.push_back(name);
    }
    const auto number = [](const std::string& text) {
        return text == "nan" ? NAN : std::atof(text.c_str());
    };
    while (std::getline(csv, line)) {
        if (line.empty()) continue;
        LogRow r;
        std::istringstream row(line);
        std::string field;
        for (size_t i = 0; i < names.size() && std::getline(row, field, ','); ++i) {
            const std::string& n = names[i];
            const double v = number(field);
            if (n == "iteration")
                r.iteration = int(v);
            else if (n == "stage")
                r.stage = int(v);
            else if (n == "loss_total")
                r.total = v;
            else if (n == "loss_view")
                r.view = v;
            else if (n == "loss_envmap")
                r.envmap = v;
            else if (n == "loss_adversarial")
                r.adversarial = v;
            else if (n == "loss_discriminator")
                r.discriminator = v;
            else if (n == "lr")
                r.learningRate = v;
            else if (n == "it_per_s")
                r.itPerSecond = v;
            else if (n == "val_psnr_db")
                r.valPsnr = v;
            else if (n == "val_angular_deg")
                r.valAngular = v;
            else if (n == "loss_voxel")
                r.voxel = v;
            else if (n == "loss_depth")
                r.depth = v;
            else if (n == "s_data")
                r.secondsData = v;
            else if (n == "s_forward")
                r.secondsForward = v;
            else if (n == "s_backward")
                r.secondsBackward = v;
            else if (n == "s_allreduce")
                r.secondsAllReduce = v;
        }
        if (r.iteration <= lastIteration) rows.push_back(r);
    }
    return rows;
}

void writeLog(const TrainOptions& o, const std::vector<LogRow>& log) {
    std::ostringstream csv;
    csv << kLogHeader << '\n';
    for (const auto& r : log)
        csv << r.iteration << ',' << r.stage << ',' << r.total << ',' << r.view << ',' << r.envmap
            << ',' << r.adversarial << ',' << r.discriminator << ',' << r.learningRate << ','
            << r.itPerSecond << ',' << r.valPsnr << ',' << r.valAngular << ',' << r.voxel << ','
            << r.depth << ',' << r.secondsData << ',' << r.secondsForward << ','
            << r.secondsBackward << ',' << r.secondsAllReduce << '\n';
    writeTextFile(o.out + ".csv", csv.str());
    CurveSeries total{"training loss (sum of the terms)", {}, {}};
    CurveSeries view{"held-out view loss", {}, {}}, env{"envmap loss", {}, {}};
    CurveSeries voxel{"voxel loss (against the oracle)", {}, {}}, depth{"MPI depth loss", {}, {}};
    CurveSeries psnr{"validation envmap PSNR (dB), all content", {}, {}};
    CurveSeries angular{"validation RGB angular error (deg)", {}, {}};
    for (const auto& r : log) {
        total.x.push_back(r.iteration), total.y.push_back(r.total);
        view.x.push_back(r.iteration), view.y.push_back(r.view);
        if (r.stage >= 2) env.x.push_back(r.iteration), env.y.push_back(r.envmap);
        if (r.voxel > 0) voxel.x.push_back(r.iteration), voxel.y.push_back(r.voxel);
        if (r.depth > 0) depth.x.push_back(r.iteration), depth.y.push_back(r.depth);
        if (std::isfinite(r.valPsnr)) {
            psnr.x.push_back(r.iteration), psnr.y.push_back(r.valPsnr);
            angular.x.push_back(r.iteration), angular.y.push_back(r.valAngular);
        }
    }
    writeCurvePlot(o.out + ".png", "lighthouse train: " + fs::path(o.out).filename().string(),
                   "iteration", nonEmpty({total, view, env, voxel, depth, psnr, angular}));
}

// Mean envmap PSNR and angular error (all content) of the current model on held-out scenes,
// rendered with the training renderer at the ground truth's size.
std::pair<double, double> validate(LighthouseNet& net, const std::vector<TrainingExample>& scenes,
                                   const torch::Device& device) {
    torch::NoGradGuard noGrad;
    net->eval();
    std::vector<double> psnrs, angles;
    for (const auto& ex : scenes) {
        const PairInputs in =
            makePairInputs(ex.ref, ex.src, ex.cameras.ref, *ex.cameras.src, *ex.cameras.near,
                           *ex.cameras.far, net->config, device);
        const PipelineOutput out = net->run(in, true);
        const auto cubes = pruneCubesStraightThrough(
            expandHighlightsInCubes(out.cubes, net->config.highlightGain), net->config.pruneAlpha);
        for (size_t e = 0; e < ex.envmaps.size(); ++e) {
            const auto& gt = ex.envmaps[e];
            const ImageRGB pred =
                tensorToImage(renderEnvmapTorch(cubes, in.layout, ex.cameras.envmaps[e].position,
                                                gt.width, gt.height, net->config.samplesPerLevel));
            const EnvmapMetrics m = compareEnvmaps(pred, gt);
            psnrs.push_back(m.psnrAll);
            angles.push_back(m.angularAll);
        }
    }
    net->train();
    return {meanStd(psnrs).mean, meanStd(angles).mean};
}

std::string formatDuration(double seconds) {
    const int s = int(std::max(0.0, seconds));
    std::ostringstream out;
    out << s / 3600 << "h" << std::setw(2) << std::setfill('0') << (s / 60) % 60 << "m"
        << std::setw(2) << s % 60 << "s";
    return out.str();
}

// One training example as tensors, augmented, with the optional direct-supervision targets.
struct PreparedExample {
    PairInputs inputs;
    PinholeCamera target;
    torch::Tensor targetImage;                  // [1, 3, H, W] linear, the held-out view
    torch::Tensor targetHdr;                    // [1, 3, H, W] its unclipped radiance; undefined
                                                // without tgt.exr
    torch::Tensor refDepth;                     // [1, 1, H, W] metres; undefined without depth.exr
    std::vector<torch::Tensor> oracle;          // cubes; empty without oracle.vdb
    torch::Tensor lampCentres;                  // [M, 3] metres; undefined unless asked for
    torch::Tensor lampCells;                    // [cells]: lampCellTarget of them; likewise
    std::vector<torch::Tensor> envmaps;         // [1, 3, h, w] linear HDR at the training size
    std::vector<torch::Tensor> envmapObserved;  // [1, 1, h, w] 0/1; only for the highlight and
                                                // lamp-light losses
    std::vector<Vec3d> envmapPositions;
};

// An observed-pixel mask at the training envmap size: the share of each new pixel's area
// that was observed, at least half of it counting as observed.
torch::Tensor maskAtSize(const std::vector<std::uint8_t>& mask, int width, int height, int newWidth,
                         int newHeight) {
    return (imageToTensor(resizeImage(maskToImage(mask, width, height), newWidth, newHeight))
                .narrow(1, 0, 1) >= 0.5f)
        .to(torch::kFloat32);
}

PreparedExample prepareExample(const std::string& directory, const NetConfig& config,
                               const TrainOptions& o, Random& rng, const torch::Device& device,
                               bool direct) {
    TrainingExample ex =
        loadExample(directory, /*withMasks=*/o.highlightWeight > 0 || o.emitterLightWeight > 0);
    Augmentation a;  // the identity unless augmenting
    if (o.augment) a = drawAugmentation(rng);
    // Expose the unclipped renders where the example has them, then clip, as a camera does
    // (net/training_data.h); without augmentation that gives the PNGs' values again.
    const bool unclipped = useUnclippedViews(ex);
    // Metering for the highlights needs the radiance above 1, which only the EXRs keep.
    if (unclipped && o.maxPhotoClipped < 1.0)
        a.exposure =
            std::min(a.exposure, exposureClippingAtMost(ex.ref, a.gain, o.maxPhotoClipped));
    ImageRGB targetHdr, refUnclipped;
    if (unclipped) {
        targetHdr = ex.tgt;
        augmentRadiance(targetHdr, a);
    }
    // The photo before its clip, exposed as the photo is, for a head that reads it.
    if (unclipped && config.emitterPhotoUnclipped) {
        refUnclipped = ex.ref;
        augmentRadiance(refUnclipped, a);
    }
    if (o.augment || unclipped) {
        augmentPhoto(ex.ref, a, rng);
        augmentPhoto(ex.src, a, rng);
        augmentPhoto(ex.tgt, a, rng);
    }
    for (auto& e : ex.envmaps) augmentRadiance(e, a);  // the identity unless augmenting or metering
    PreparedExample p;
    p.inputs = makePairInputs(ex.ref, ex.src, ex.cameras.ref, *ex.cameras.src, *ex.cameras.near,
                              *ex.cameras.far, config, device);
    if (!refUnclipped.pixels.empty())
        p.inputs.refUnclipped =
            photoRadianceTensor(refUnclipped, config.width, config.height).to(device);
    p.target = ex.cameras.tgt->resized(config.width, config.height);
    p.targetImage = imageToTensor(resizeImage(ex.tgt, config.width, config.height)).to(device);
    if (unclipped)
        p.targetHdr = imageToTensor(resizeImage(targetHdr, config.width, config.height)).to(device);
    for (size_t e = 0; e < ex.envmaps.size(); ++e) {
        p.envmaps.push_back(
            imageToTensor(resizeImage(ex.envmaps[e], config.trainEnvWidth, config.trainEnvHeight))
                .to(device));
        p.envmapPositions.push_back(ex.cameras.envmaps[e].position);
        if (e < ex.masks.size())
            p.envmapObserved.push_back(maskAtSize(ex.masks[e], ex.envmaps[e].width,
                                                  ex.envmaps[e].height, config.trainEnvWidth,
                                                  config.trainEnvHeight)
                                           .to(device));
    }
    if (!direct) return p;
    const fs::path dir(directory);
    if (fs::is_regular_file(dir / dataset::kDepth))
        p.refDepth = imageToTensor(resizeImage(readImage((dir / dataset::kDepth).string()),
                                               config.width, config.height))
                         .narrow(1, 0, 1)
                         .to(device);
    if ((o.emitterPositionWeight > 0 || o.emitterCellWeight > 0) &&
        fs::is_regular_file(dir / dataset::kScene)) {
        const torch::Tensor centres = lampCentresOfScene((dir / dataset::kScene).string());
        if (centres.defined()) {
            p.lampCentres = centres.to(device);
            const torch::Tensor cellLamps =
                o.lampCellsUnseenOnly ? lampsOutsideView(centres, ex.cameras.ref) : centres;
            if (cellLamps.defined())
                p.lampCells =
                    lampCellTarget(cellLamps, *ex.cameras.far, kEmitterCellsPerSide).to(device);
        }
    }
    if (fs::is_regular_file(dir / dataset::kOracle)) {
        p.oracle = loadOracleCubes((dir / dataset::kOracle).string(), p.inputs.layout, device);
        const auto gains =
            torch::tensor({float(a.factor(0)), float(a.factor(1)), float(a.factor(2)), 1.f})
                .view({1, 4, 1, 1, 1})
                .to(device);
        for (auto& c : p.oracle)
            c = c * gains;  // the scene's light, exposed and balanced as the photos
    }
    return p;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void train(const TrainOptions& o, std::ostream& progressOfEveryRank) {
    o.validate();
    // Data-parallel: the rendezvous first, so that a rank with bad options fails every rank
    // soon; only rank 0 reports progress and writes files.
    std::unique_ptr<Communicator> comm;
    if (o.distributed.active()) comm = std::make_unique<Communicator>(o.distributed);
    const bool root = !comm || comm->rank() == 0;
    const int world = comm ? comm->worldSize() : 1, rank = comm ? comm->rank() : 0;
    std::ostream discard(nullptr);
    std::ostream& progress = root ? progressOfEveryRank : discard;
    setTorchThreads(o.threads);
    const torch::Device device = selectDevice(o.device);
    torch::manual_seed(o.seed);
    const bool direct = o.supervision == "direct";

    std::vector<std::string> trainDirs = listExamples(o.data), validationDirs;
    const std::vector<std::string> everyDir = trainDirs;  // before the exposure filter
    if (o.maxClipped < 1.0) {
        const std::size_t all = trainDirs.size();
        trainDirs = withoutOverexposedScenes(trainDirs, o.maxClipped, progress);
        progress << "train: left out " << all - trainDirs.size() << " of " << all
                 << " scenes with an envmap clipped on more than " << o.maxClipped
                 << " of its pixels\n";
        if (trainDirs.empty())
            throw InputError("--max-clipped " + std::to_string(o.maxClipped) +
                             " leaves no scene of '" + o.data + "'; raise it");
    }
    if (!o.validation.empty()) {
        validationDirs = listExamples(o.validation);
    } else {
        if (trainDirs.size() < 2)
            throw InputError(
                "need at least 2 examples to hold one out for validation (or pass --val)");
        const size_t held = std::max<size_t>(1, trainDirs.size() / 20);
        validationDirs.assign(trainDirs.end() - long(held), trainDirs.end());
        trainDirs.resize(trainDirs.size() - held);
    }
    std::vector<TrainingExample> validationScenes;
    for (size_t i = 0; i < validationDirs.size() && int(i) < o.validationScenes; ++i)
        validationScenes.push_back(loadExample(validationDirs[i]));
    if (!fs::path(o.out).parent_path().empty())
        fs::create_directories(fs::path(o.out).parent_path());

    TrainingState s;
    NetConfig netConfig = o.configOverride ? *o.configOverride : NetConfig::byName(o.config);
    if (o.pretrainLampCellEpochs > 0 && !netConfig.emitterPhotoCells)
        throw InputError(
            "--pretrain-lamp-cells trains the photo classifier of a '+cells' emitter "
            "head: use a --config such as wide+emitters+photo+cells");
    if (o.emitterLightWeight > 0 && netConfig.emitters == 0)
        throw InputError(
            "--emitter-light-weight supervises an emitter head's lamps: use a --config with "
            "'+emitters', such as wide+emitters+photo+cells+apart");
    netConfig.pruneAlpha = o.pruneAlpha;
    netConfig.highlightGain = o.highlightGain;
    s.net = LighthouseNet(netConfig);
    s.net->to(device);
    s.average = LighthouseNet(s.net->config);
    s.average->to(device);
    s.average->eval();
    copyWeights(s.average, s.net);
    s.discriminator = PatchDiscriminator();
    s.discriminator->to(device);
    makeNetOptimizer(s, o.learningRate, o.pretrainLampCellEpochs > 0);
    s.discriminatorOptimizer = std::make_unique<torch::optim::Adam>(
        s.discriminator->parameters(), torch::optim::AdamOptions(o.learningRate).betas({0.0, 0.9}));
    const bool resumed = loadCheckpoint(o, s);
    if (resumed) {
        progress << "train: resuming from " << o.checkpointPath() << " at iteration " << s.iteration
                 << "\n";
        s.log = readLog(o.out + ".csv", s.iteration);
    } else if (!o.init.empty()) {
        // Fine-tuning: the weights of a model of the same configuration, a fresh optimiser.
        LighthouseNet start = loadModel(o.init, device);
        if (start->config.sameParameters(s.net->config)) {
            copyWeights(s.net, start);
            progress << "train: no checkpoint at " << o.checkpointPath() << "; fine-tuning from "
                     << o.init << " with a fresh optimiser\n";
        } else if (o.initWiden) {
            widenModel(s.net, start);
            progress << "train: no checkpoint at " << o.checkpointPath() << "; starting from "
                     << o.init << " widened (each completion channel split in two: the same "
                     << "predictions) with a fresh optimiser\n";
        } else if (o.initPartial) {
            const MatchedWeights m = copyMatchingWeights(s.net, start);
            if (m.copied == 0)
                throw InputError(
                    "--init '" + o.init + "' (a '" + start->config.name +
                    "' model) shares no parameter of this name and shape with --config " +
                    o.config);
            progress << "train: no checkpoint at " << o.checkpointPath() << "; starting from the "
                     << m.copied << " of " << m.tensors << " tensors (" << m.copiedValues << " of "
                     << m.values << " values) of " << o.init << " that match in name and shape";
            if (m.extended > 0)
                progress << " or only gained input channels (" << m.extended
                         << " stems; the new inputs weighted zero)";
            progress << "; the rest start fresh\n";
        } else {
            throw InputError("--init '" + o.init + "' is a '" + start->config.name +
                             "' model with other sizes than --config " + o.config +
                             " (--init-widen starts a wider model from the same function, "
                             "--init-partial from the parameters they share)");
        }
        copyWeights(s.average, s.net);
        if (start->config.colourAnchor != s.net->config.colourAnchor)
            progress << "train: --init has " << (start->config.colourAnchor ? "a" : "no")
                     << " colour anchor; this run trains "
                     << (s.net->config.colourAnchor ? "with" : "without") << " one\n";
    }
    const NetConfig& config = s.net->config;
    if (!resumed && o.pretrainLampCellEpochs > 0) {
        // Before the first step: a resumed run has the pretrained weights in its checkpoint.
        // Every scene that is not held out: what --max-clipped leaves out is too bright an
        // exposure for the envmap losses, and its photo says as much about its lamps.
        std::vector<std::string> photoDirs;
        for (const auto& dir : everyDir)
            if (std::find(validationDirs.begin(), validationDirs.end(), dir) ==
                validationDirs.end())
                photoDirs.push_back(dir);
        pretrainPhotoClassifier(o, s, photoDirs, validationDirs, progress);
        copyWeights(s.average, s.net);
    }
    if (comm) {
        // Every rank starts from rank 0's weights, at its iteration, on the same data.
        std::vector<torch::Tensor> weights = s.net->parameters();
        for (const auto& p : s.discriminator->parameters()) weights.push_back(p);
        {
            torch::NoGradGuard noGrad;
            comm->broadcastFromRankZero(weights, "the broadcast of rank 0's weights");
        }
        const long long iteration0 =
            comm->broadcastValue(s.iteration, "the check of the checkpoints");
        const long long scenes0 =
            comm->broadcastValue((long long)trainDirs.size(), "the check of the data");
        if (iteration0 != s.iteration)
            throw FileError("rank " + std::to_string(rank) + " starts at iteration " +
                            std::to_string(s.iteration) + " but rank 0 at " +
                            std::to_string(iteration0) +
                            ": every rank must read the same checkpoint '" + o.checkpointPath() +
                            "' (a shared file system)");
        if (scenes0 != (long long)trainDirs.size())
            throw FileError("rank " + std::to_string(rank) + " sees " +
                            std::to_string(trainDirs.size()) + " training scenes in '" + o.data +
                            "' but rank 0 " + std::to_string(scenes0) +
                            ": every rank must read the same data set (a shared file system)");
        std::size_t count = 0;
        for (const auto& p : s.net->parameters()) count += std::size_t(p.numel());
        progressOfEveryRank << "train: rank " << rank << " of " << world << " joined at "
                            << o.distributed.masterAddress << ":" << o.distributed.masterPort
                            << "; examples " << rank * (o.batch / world) << ".."
                            << (rank + 1) * (o.batch / world) - 1 << " of each batch of " << o.batch
                            << "; " << count << " parameters (" << count * 4 / 1e6
                            << " MB) all-reduced per step\n";
    }
    progress << "train: config " << config.name << " (" << config.width << "x" << config.height
             << " input, " << config.planes << " planes, " << config.levels << " x "
             << config.resolution << "^3), " << trainDirs.size() << " training scenes, "
             << validationDirs.size() << " held out (" << validationScenes.size() << " validated), "
             << torch::get_num_threads() << (torch::get_num_threads() == 1 ? " thread" : " threads")
             << " on " << device.str() << ", " << o.supervision << " supervision"
             << (o.augment ? ", augmented" : "") << "\n";

    std::unique_ptr<VggPerceptualLoss> vgg;
    if (!o.vggWeights.empty()) vgg = std::make_unique<VggPerceptualLoss>(o.vggWeights, device);
    progress << "train: image loss: "
             << (vgg ? "VGG-19 perceptual (" + o.vggWeights + ")"
                     : std::string("L1 + gradients (substitute for VGG-19)"))
             << "; envmaps also " << o.irradianceWeight << " x irradiance";
    if (o.irradianceFocus > 0)
        progress << " (gradient focused on bright pixels, power " << o.irradianceFocus << ")";
    if (o.envmapSquaredWeight > 0) progress << ", " << o.envmapSquaredWeight << " x squared sRGB";
    if (o.highlightWeight > 0)
        progress << ", " << o.highlightWeight << " x highlights (observed lamps and windows)";
    if (o.coarseEnvmapWeight > 0)
        progress << ", " << o.coarseEnvmapWeight << " x HDR over " << o.coarseEnvmapBlock << "x"
                 << o.coarseEnvmapBlock << " blocks";
    if (o.viewHdrWeight > 0)
        progress << "; views also " << o.viewHdrWeight << " x HDR (unclipped tgt.exr)";
    if (o.maxPhotoClipped < 1.0)
        progress << "; photos exposed to clip on at most " << o.maxPhotoClipped
                 << " of the reference view";
    if (o.highlightGain != 1.0) progress << "; cubes under a highlight gain of " << o.highlightGain;
    if (o.pruneAlpha > 0)
        progress << "; envmaps rendered with voxels of alpha below " << o.pruneAlpha
                 << " pruned (straight-through)";
    if (o.alphaBinaryWeight > 0)
        progress << "; cubes also " << o.alphaBinaryWeight << " x alpha (1 - alpha)";
    if (o.emitterPositionWeight > 0)
        progress << "; emitter head also " << o.emitterPositionWeight
                 << " x squared distance to the nearest true lamp or window (scene.json)";
    if (o.emitterCellWeight > 0)
        progress << "; emitter head also " << o.emitterCellWeight
                 << " x divergence of its cells from the true lamps' and windows' (scene.json)"
                 << (o.lampCellsUnseenOnly ? ", those the photo does not show" : "");
    if (o.emitterLightWeight > 0)
        progress << "; emitter head also " << o.emitterLightWeight
                 << " x error of its lamps' axis irradiance against the envmaps' unobserved "
                    "highlights' (log short of it, linear beyond)";
    if (o.directAdversarialWeight > 0)
        progress << "; envmaps also " << o.directAdversarialWeight
                 << " x the PatchGAN generator loss, from the first step";
    // The generator loss's weight wherever stage 3 runs: the paper's, or the direct one.
    const double adversarialWeight = direct ? o.directAdversarialWeight : kAdversarialWeight;
    if (o.adversarialInput == "log" && adversarialWeight > 0)
        progress << "; the discriminator sees ln(1 + radiance), not clamped sRGB";
    if (o.closureWeight > 0)
        progress << "; envmaps also " << o.closureWeight
                 << " x the transmittance left behind the volume (closed rooms)";
    progress << "\n";
    const auto seenByDiscriminator = [&](const torch::Tensor& envmap) {
        return o.adversarialInput == "log" ? logRadianceEncode(envmap) : srgbEncodeTensor(envmap);
    };
    const auto lossOf = [&](const torch::Tensor& predicted, const torch::Tensor& target) {
        return vgg ? (*vgg)(predicted, target) : imageLoss(predicted, target);
    };

    s.net->train();
    LogRow window;
    int windowCount = 0;
    auto windowStart = std::chrono::steady_clock::now();
    const auto runStart = windowStart;
    const int firstIteration = s.iteration;
    const int sittingEnd =
        o.stopAfter > 0 ? std::min(o.iterations, firstIteration + o.stopAfter) : o.iterations;
    for (; s.iteration < sittingEnd; ++s.iteration) {
        const int it = s.iteration;
        const int stage = stageAt(it, o.iterations, direct, adversarialWeight > 0);
        const double lr =
            it >= int(kLowLearningRateStart * o.iterations) ? o.learningRate / 10 : o.learningRate;
        setLearningRate(*s.optimizer, lr, s.learningRateScales);
        setLearningRate(*s.discriminatorOptimizer, lr);

        // Everything random in this iteration comes from (seed, iteration, example of the batch).
        const int perRank = o.batch / world;
        const double commBefore = comm ? comm->communicationSeconds() : 0;
        // total, view, envmap, adversarial, discriminator, voxel, depth, emitter cells, light
        double sums[kLossTerms] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        s.optimizer->zero_grad();
        for (int j = rank * perRank; j < (rank + 1) * perRank; ++j) {
            Random rng(j == 0 ? mixSeed(o.seed, uint64_t(it))
                              : mixSeed(mixSeed(o.seed, uint64_t(it)), uint64_t(j)));
            auto clock = std::chrono::steady_clock::now();
            const std::string& dir = trainDirs[size_t(rng.integer(0, int(trainDirs.size()) - 1))];
            const PreparedExample ex = prepareExample(dir, config, o, rng, device, direct);
            const size_t e = size_t(rng.integer(0, int(ex.envmaps.size()) - 1));
            window.secondsData += secondsSince(clock);

            clock = std::chrono::steady_clock::now();
            PipelineOutput out = s.net->run(ex.inputs, stage >= 2);
            // The cubes as predict exports them: every loss on them sees the gained lamps.
            out.cubes = expandHighlightsInCubes(out.cubes, config.highlightGain);
            const auto view = renderMpiView(out.mpi, ex.inputs.depths, ex.inputs.ref, ex.target);
            auto viewLoss = lossOf(view, ex.targetImage);
            if (o.viewHdrWeight > 0 && ex.targetHdr.defined())
                viewLoss = viewLoss + o.viewHdrWeight * hdrImageLoss(view, ex.targetHdr);
            auto loss = viewLoss;
            torch::Tensor envLoss = torch::zeros({}), advLoss = torch::zeros({}),
                          discLoss = torch::zeros({});
            torch::Tensor voxLoss = torch::zeros({}), depthLoss = torch::zeros({});
            torch::Tensor cellLoss = torch::zeros({});   // emitterCellLoss, unweighted
            torch::Tensor lightLoss = torch::zeros({});  // emitterLightLoss, unweighted
            if (ex.refDepth.defined()) {
                depthLoss = mpiDepthLoss(out.mpi, ex.inputs.depths, ex.refDepth);
                loss = loss + depthLoss;
            }
            if (stage >= 2) {
                // Every envmap of the example: the completion's forward and backward cost the same
                // for one or all, and each one is a room seen from another point. The adversarial
                // stage uses the one drawn for this iteration.
                torch::Tensor env;
                const auto renderedCubes = pruneCubesStraightThrough(out.cubes, config.pruneAlpha);
                for (size_t k = 0; k < ex.envmaps.size(); ++k) {
                    const TorchEnvmap envmap = renderEnvmapAndTransmittanceTorch(
                        renderedCubes, ex.inputs.layout, ex.envmapPositions[k],
                        config.trainEnvWidth, config.trainEnvHeight, config.samplesPerLevel);
                    const torch::Tensor& rendered = envmap.radiance;
                    if (o.closureWeight > 0)
                        envLoss = envLoss + o.closureWeight * closureLoss(envmap.transmittance);
                    envLoss = envLoss + lossOf(rendered, ex.envmaps[k]) +
                              hdrImageLoss(rendered, ex.envmaps[k]) +
                              o.irradianceWeight *
                                  focusedIrradianceLoss(rendered, ex.envmaps[k], o.irradianceFocus);
                    if (o.highlightWeight > 0 && k < ex.envmapObserved.size())
                        envLoss =
                            envLoss + o.highlightWeight * highlightLoss(rendered, ex.envmaps[k],
                                                                        ex.envmapObserved[k]);
                    if (o.coarseEnvmapWeight > 0)
                        envLoss = envLoss +
                                  o.coarseEnvmapWeight * coarseHdrImageLoss(rendered, ex.envmaps[k],
                                                                            o.coarseEnvmapBlock);
                    if (o.envmapSquaredWeight > 0)
                        envLoss = envLoss +
                                  o.envmapSquaredWeight * squaredImageLoss(rendered, ex.envmaps[k]);
                    if (k == e) env = rendered;
                }
                const auto& gt = ex.envmaps[e];
                loss = loss + envLoss;
                if (!ex.oracle.empty()) {
                    voxLoss = voxelLoss(out.cubes, ex.oracle);
                    loss = loss + voxLoss;
                }
                if (!direct) loss = loss + kSparsityWeight * sparsityLoss(out.cubes);
                if (o.alphaBinaryWeight > 0)
                    loss = loss + o.alphaBinaryWeight * binaryAlphaLoss(out.cubes);
                if (o.emitterPositionWeight > 0 && out.emitters.position.defined() &&
                    ex.lampCentres.defined())
                    loss = loss + o.emitterPositionWeight *
                                      emitterPositionLoss(out.emitters.position, ex.lampCentres);
                if (o.emitterCellWeight > 0 && out.emitters.cellLogits.defined() &&
                    ex.lampCells.defined()) {
                    cellLoss = emitterCellLoss(out.emitters.cellLogits, ex.lampCells);
                    loss = loss + o.emitterCellWeight * cellLoss;
                }
                if (o.emitterLightWeight > 0 && out.emitters.position.defined()) {
                    // The lamps' light as predict exports it: pruned where the model's volumes
                    // are.
                    lightLoss =
                        emitterLightLoss(out.emitters, ex.inputs.layout, defaultPruneAlpha(config),
                                         ex.envmapPositions, ex.envmaps, ex.envmapObserved);
                    loss = loss + o.emitterLightWeight * lightLoss;
                }
                if (stage >= 3) {
                    // Discriminator step on real vs (detached) predicted envmaps, then the
                    // generator term. Data-parallel: one step per example of the rank's slice, on
                    // the mean of the ranks' gradients.
                    s.discriminatorOptimizer->zero_grad();
                    discLoss =
                        discriminatorHingeLoss(s.discriminator(seenByDiscriminator(gt)),
                                               s.discriminator(seenByDiscriminator(env.detach())));
                    (world > 1 ? discLoss / world : discLoss).backward();
                    zeroNonFiniteGradients(s.discriminator->parameters());
                    if (comm)
                        comm->allReduceGradients(s.discriminator->parameters(),
                                                 "the discriminator's all-reduce");
                    s.discriminatorOptimizer->step();
                    advLoss = generatorHingeLoss(s.discriminator(seenByDiscriminator(env)));
                    loss = loss + adversarialWeight * advLoss;
                }
            }
            window.secondsForward += secondsSince(clock);
            clock = std::chrono::steady_clock::now();
            (o.batch > 1 ? loss / o.batch : loss).backward();
            window.secondsBackward += secondsSince(clock);
            const torch::Tensor* terms[kLossTerms] = {&loss,      &viewLoss, &envLoss,
                                                      &advLoss,   &discLoss, &voxLoss,
                                                      &depthLoss, &cellLoss, &lightLoss};
            for (int t = 0; t < kLossTerms; ++t) sums[t] += terms[t]->item<double>() / o.batch;
        }
        auto clock = std::chrono::steady_clock::now();
        zeroNonFiniteGradients(s.net->parameters());
        if (comm) {
            comm->allReduceGradients(s.net->parameters(), "the gradients' all-reduce");
            std::vector<torch::Tensor> losses = {
                torch::tensor(std::vector<double>(sums, sums + kLossTerms), torch::kFloat64)
                    .to(device)};
            comm->allReduceSum(losses, "the losses' all-reduce");
            for (int t = 0; t < kLossTerms; ++t) sums[t] = losses[0][t].item<double>();
            window.secondsAllReduce += comm->communicationSeconds() - commBefore;
        }
        torch::nn::utils::clip_grad_norm_(s.net->parameters(), kGradientClipNorm);
        s.optimizer->step();
        updateWeightAverage(s.average, s.net, o.averageDecay);
        s.discriminator->zero_grad();  // the generator term left gradients in the discriminator
        window.secondsBackward += secondsSince(clock);

        window.total += sums[0];
        window.view += sums[1];
        window.envmap += sums[2];
        window.adversarial += sums[3];
        window.discriminator += sums[4];
        window.voxel += sums[5];
        window.depth += sums[6];
        window.emitterCells += sums[7];
        window.emitterLight += sums[8];
        ++windowCount;

        const int done = it + 1;
        const bool logNow = done % o.logEvery == 0 || done == o.iterations || done == sittingEnd;
        const bool validateNow = done % o.validateEvery == 0 || done == o.iterations;
        if (logNow) {
            const auto now = std::chrono::steady_clock::now();
            LogRow row;
            row.iteration = done;
            row.stage = stage;
            row.total = window.total / windowCount;
            row.view = window.view / windowCount;
            row.envmap = window.envmap / windowCount;
            row.adversarial = window.adversarial / windowCount;
            row.discriminator = window.discriminator / windowCount;
            row.voxel = window.voxel / windowCount;
            row.depth = window.depth / windowCount;
            row.emitterCells = window.emitterCells / windowCount;
            row.emitterLight = window.emitterLight / windowCount;
            row.secondsData = window.secondsData / windowCount;
            row.secondsForward = window.secondsForward / windowCount;
            row.secondsBackward = window.secondsBackward / windowCount;
            row.secondsAllReduce = window.secondsAllReduce / windowCount;
            row.learningRate = lr;
            row.itPerSecond =
                windowCount / std::chrono::duration<double>(now - windowStart).count();
            if (validateNow && root)
                std::tie(row.valPsnr, row.valAngular) =
                    validate(s.average, validationScenes, device);
            const double elapsed = std::chrono::duration<double>(now - runStart).count();
            const double eta = elapsed / std::max(1, done - firstIteration) * (o.iterations - done);
            progress << "train: it " << done << "/" << o.iterations << "  stage " << stage
                     << "  loss " << std::fixed << std::setprecision(4) << row.total << " (view "
                     << row.view << ", envmap " << row.envmap;
            if (direct) progress << ", voxel " << row.voxel << ", depth " << row.depth;
            if (!direct || stage >= 3) progress << ", adv " << row.adversarial;
            if (stage >= 3) progress << ", discriminator " << row.discriminator;
            if (o.emitterCellWeight > 0) progress << ", emitter cells " << row.emitterCells;
            if (o.emitterLightWeight > 0) progress << ", emitter light " << row.emitterLight;
            progress << ")  " << std::setprecision(2) << row.itPerSecond << " it/s (data "
                     << row.secondsData << " s, forward " << row.secondsForward << " s, backward "
                     << row.secondsBackward << " s";
            if (comm) progress << ", all-reduce " << row.secondsAllReduce << " s";
            progress << ")  ETA " << formatDuration(eta);
            if (validateNow)
                progress << "  val PSNR " << row.valPsnr << " dB, angular " << row.valAngular
                         << " deg";
            progress << std::defaultfloat << std::endl;
            s.log.push_back(row);
            window = LogRow{};
            windowCount = 0;
            windowStart = std::chrono::steady_clock::now();
            if (root)
                writeLog(o, s.log);  // every progress line, so a resumed run keeps whole curves
        }
        if (done % o.checkpointEvery == 0 || done == o.iterations || done == sittingEnd) {
            s.iteration = done;
            if (root) saveCheckpoint(o, s);
            s.iteration = it;
        }
    }
    if (sittingEnd < o.iterations) {
        progress << "train: stopped at iteration " << sittingEnd << " of " << o.iterations
                 << " (--stop-after); "
                 << "the same command resumes from " << o.checkpointPath() << "\n";
        return;
    }
    s.iteration = o.iterations;
    if (!root) return;
    saveModel(s.average, o.out, o.halfModel);
    writeLog(o, s.log);
    progress << "train: wrote " << o.out << " (log " << o.out << ".csv, curves " << o.out
             << ".png)\n";
}

}  // namespace lh::net
