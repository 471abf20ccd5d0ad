#include "net/predictor.h"

#include "core/errors.h"
#include "image/image_io.h"
#include "image/luminance.h"
#include "net/device.h"
#include "net/highlight_gain.h"
#include "net/lighthouse_net.h"
#include "net/volume_export.h"
#include "net/volume_render.h"
#include "render/radial_shell.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

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

namespace {

// Analysis: each clipped photo pixel whose true luminance is at least 2, put into every level
// at its true 3D point (true z-depth) as an opaque voxel of its true radiance: the lamps the
// photo shows with their true shape (a ceiling panel flat, not facing the camera).
void splatObservedLamps(std::vector<torch::Tensor>& cubes, const VolumeLayout& layout,
                        const ImageRGB& photo, const ImageRGB& truth, const ImageRGB& depth,
                        const PinholeCamera& camera) {
    std::vector<torch::Tensor> cpu;
    for (const auto& c : cubes) cpu.push_back(c.to(torch::kCPU).contiguous().clone());
    int splatted = 0;
    for (int y = 0; y < photo.height; ++y)
        for (int x = 0; x < photo.width; ++x) {
            const float* p = photo.at(x, y);
            if (std::max({p[0], p[1], p[2]}) < 0.99f) continue;
            const float* t = truth.at(x, y);
            if (rec709Luminance(t) < 2.0) continue;
            const double z = depth.at(x, y)[0];
            const Vec3d point((x + 0.5 - camera.cx) / camera.fx * z,
                              (y + 0.5 - camera.cy) / camera.fy * z, z);
            ++splatted;
            for (int k = 0; k < layout.levels; ++k) {
                const WorldBox box = layout.box(k);
                if (!box.contains(point)) continue;
                const double v = layout.voxelSize(k);
                const int r = layout.resolution;
                const int ix = std::min(r - 1, int((point.x() - box.min.x()) / v));
                const int iy = std::min(r - 1, int((point.y() - box.min.y()) / v));
                const int iz = std::min(r - 1, int((point.z() - box.min.z()) / v));
                auto a = cpu[k].accessor<float, 5>();
                for (int c = 0; c < 3; ++c) a[0][c][iz][iy][ix] = t[c];
                a[0][3][iz][iy][ix] = 1.0f;
            }
        }
    std::fprintf(stderr, "analysis: %d observed lamp pixels splatted\n", splatted);
    for (size_t k = 0; k < cubes.size(); ++k) cubes[k] = cpu[k].to(cubes[k].device());
}

}  // namespace

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
    PipelineOutput out = impl_->net->run(inputs, true);
    if (const char* truthPath = std::getenv("LH_SPLAT_TRUTH"))
        splatObservedLamps(out.cubes, inputs.layout, pair.ref, readImage(truthPath),
                           readImage(std::getenv("LH_SPLAT_DEPTH")), cams.ref);
    // The gain on the cubes, as training applies it, before they become grids.
    result.volume = cubesToVolume(
        expandHighlightsInCubes(out.cubes, impl_->highlightGain, impl_->highlightKnee),
        inputs.layout, impl_->pruneAlpha);
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
    result.volume.refCamera = cams.ref;
    result.mpiOnly.refCamera = cams.ref;
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace lh::net
