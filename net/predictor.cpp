#include "net/predictor.h"

#include "core/errors.h"
#include "net/device.h"
#include "net/highlight_gain.h"
#include "net/lighthouse_net.h"
#include "net/volume_export.h"
#include "net/volume_render.h"
#include "render/radial_shell.h"

#include <chrono>
#include <cmath>
#include <cstdio>

namespace lh::net {

std::string defaultModelPath() { return LIGHTHOUSE_DEFAULT_MODEL; }

float defaultPruneAlpha(const NetConfig& config) {
    return config.pruneAlpha > 0 ? float(config.pruneAlpha) : kDefaultPruneAlpha;
}

void validateStereoPair(const StereoPair& pair) {
    const CamerasFile& c = pair.cameras;
    if (!c.src)
        throw InputError(
            "cameras.json has no 'src' camera: prediction needs the second image's camera");
    const auto checkImage = [](const ImageRGB& im, const PinholeCamera& cam, const char* name) {
        if (im.width != cam.width || im.height != cam.height)
            throw InputError(std::string(name) + " image is " + std::to_string(im.width) + "x" +
                             std::to_string(im.height) + " but cameras.json says " +
                             std::to_string(cam.width) + "x" + std::to_string(cam.height));
        for (float v : im.pixels)
            if (!std::isfinite(v))
                throw InputError(std::string(name) + " image holds NaN or infinite values");
    };
    checkImage(pair.ref, c.ref, "reference");
    checkImage(pair.src, *c.src, "source");
    const double baseline = (c.src->position - c.ref.position).length();
    if (!(baseline > 1e-9))
        throw InputError(
            "the two cameras are at the same place (zero baseline): a stereo pair needs two "
            "viewpoints");
    if (c.near && c.far && !(*c.near > 0 && *c.far > *c.near))
        throw InputError("cameras.json needs 0 < near < far");
}

std::vector<std::string> stereoPairWarnings(const StereoPair& pair) {
    std::vector<std::string> warnings;
    const CamerasFile& c = pair.cameras;
    if (!c.src) return warnings;
    const double baseline = (c.src->position - c.ref.position).length();
    char text[200];
    if (baseline > kImplausibleBaseline) {
        std::snprintf(text, sizeof text,
                      "the source camera is %.3g m from the reference; a stereo pair for this "
                      "method is 5-15 cm "
                      "apart (check cameras.json's units and that cam_to_world is camera-to-world)",
                      baseline);
        warnings.push_back(text);
    } else if (c.near && baseline > *c.near) {
        std::snprintf(text, sizeof text,
                      "the baseline (%.3g m) exceeds the nearest depth (%.3g m): the views hardly "
                      "overlap there",
                      baseline, *c.near);
        warnings.push_back(text);
    }
    // The same photo given twice has no parallax: the plane sweep then sees every depth as
    // equally consistent, and the MPI's depths are guesses.
    if (pair.ref.width == pair.src.width && pair.ref.height == pair.src.height &&
        pair.ref.pixels == pair.src.pixels)
        warnings.push_back(
            "the reference and source images are identical: with no parallax the network cannot "
            "see depth (give the second photo of the pair as --src)");
    return warnings;
}

struct Predictor::Impl {
    torch::Device device{torch::kCPU};
    LighthouseNet net{nullptr};
    float pruneAlpha = kDefaultPruneAlpha;
    bool shell = false;
    double highlightGain = 1.0;
    double highlightKnee = 1.0;
};

Predictor::Predictor(const PredictorOptions& options) : impl_(std::make_unique<Impl>()) {
    setTorchThreads(options.threads);
    impl_->device = selectDevice(options.device);
    if (!(options.pruneAlpha < 1))  // NaN too
        throw InputError("--prune-alpha must be in [0, 1)");
    if (!(options.highlightGain < 0)) validateHighlightGain(options.highlightGain);  // NaN too
    validateHighlightKnee(options.highlightKnee);
    if (!options.untrainedConfig.empty()) {
        impl_->net = LighthouseNet(NetConfig::byName(options.untrainedConfig));
        impl_->net->to(impl_->device);
        impl_->net->eval();
    } else {
        impl_->net =
            loadModel(options.model.empty() ? defaultModelPath() : options.model, impl_->device);
    }
    impl_->pruneAlpha =
        options.pruneAlpha >= 0 ? options.pruneAlpha : defaultPruneAlpha(impl_->net->config);
    impl_->shell = options.shell;
    impl_->highlightGain =
        options.highlightGain >= 0 ? options.highlightGain : impl_->net->config.highlightGain;
    impl_->highlightKnee = options.highlightKnee;
}

float Predictor::pruneAlpha() const { return impl_->pruneAlpha; }

double Predictor::highlightGain() const { return impl_->highlightGain; }

double Predictor::highlightKnee() const { return impl_->highlightKnee; }

Predictor::~Predictor() = default;

const NetConfig& Predictor::config() const { return impl_->net->config; }

Prediction Predictor::predict(const StereoPair& pair) const {
    validateStereoPair(pair);
    Prediction result;
    const CamerasFile& cams = pair.cameras;
    if (cams.near && cams.far) {
        result.range.near = *cams.near;
        result.range.far = *cams.far;
    } else {
        result.range = estimateDepthRange(pair.ref, pair.src, cams.ref, *cams.src);
        result.rangeEstimated = true;
    }
    const NetConfig& config = impl_->net->config;
    const auto start = std::chrono::steady_clock::now();
    const PairInputs inputs =
        makePairInputs(pair.ref, pair.src, cams.ref, *cams.src, result.range.near, result.range.far,
                       config, impl_->device);
    torch::NoGradGuard noGrad;
    const PipelineOutput out = impl_->net->run(inputs, true);
    // The gain on the cubes, as training applies it, before they become grids.
    result.volume = cubesToVolume(
        expandHighlightsInCubes(out.cubes, impl_->highlightGain, impl_->highlightKnee),
        inputs.layout, impl_->pruneAlpha);
    // Before the shell, which keeps the medium this camera sees.
    result.volume.refCamera = cams.ref;
    if (impl_->shell)
        result.volume = collapseToShell(result.volume, defaultShellCentre(inputs.layout));
    if (out.emitters.position.defined()) {
        const auto position = out.emitters.position.to(torch::kCPU, torch::kFloat64);
        const auto radiance = out.emitters.radiance.to(torch::kCPU, torch::kFloat64);
        for (int64_t k = 0; k < position.size(0); ++k)
            result.emitters.push_back(
                {Vec3d(position[k][0].item<double>(), position[k][1].item<double>(),
                       position[k][2].item<double>()),
                 out.emitters.radius[k].item<double>(), out.emitters.alpha[k].item<double>(),
                 Vec3d(radiance[k][0].item<double>(), radiance[k][1].item<double>(),
                       radiance[k][2].item<double>())});
    }
    result.mpiOnly = cubesToVolume(out.mpiCubes, inputs.layout);
    result.mpi = tensorToMpi(out.mpi, inputs.ref, inputs.depths);
    result.mpiOnly.refCamera = cams.ref;
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace lh::net
