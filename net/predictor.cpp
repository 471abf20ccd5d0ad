#include "net/predictor.h"

#include "core/errors.h"
#include "image/image_io.h"
#include "image/luminance.h"
#include "image/resample.h"
#include "net/device.h"
#include "net/emitter_head.h"
#include "net/emitter_light.h"
#include "net/highlight_gain.h"
#include "net/lighthouse_net.h"
#include "net/tensor_image.h"
#include "net/volume_export.h"
#include "net/volume_render.h"
#include "render/radial_shell.h"

#include <algorithm>
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
    bool collapseClipped = false;
    std::string clippedRadianceFrom;
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
    impl_->collapseClipped = options.collapseClipped;
    impl_->clippedRadianceFrom = options.clippedRadianceFrom;
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

// Analysis: the photo's clipped blobs whose true mean luminance is lamp-bright (>= 2), each as
// an emitter blob at its true depth, sending toward the camera the intensity the true photo
// shows (sum over its pixels of L (z / f)^2).
Emitters observedLampBlobs(const ImageRGB& photo, const ImageRGB& truth, const ImageRGB& depth,
                           const PinholeCamera& camera, const VolumeLayout& layout,
                           float pruneAlpha) {
    const int w = photo.width, h = photo.height;
    std::vector<int> label(size_t(w) * h, -1);
    const auto clipped = [&](int x, int y) {
        const float* p = photo.at(x, y);
        return std::max({p[0], p[1], p[2]}) >= 0.99f;
    };
    std::vector<float> pos, rad, radius;
    int count = 0;
    for (int y0 = 0; y0 < h; ++y0)
        for (int x0 = 0; x0 < w; ++x0) {
            if (!clipped(x0, y0) || label[size_t(y0) * w + x0] >= 0) continue;
            std::vector<std::pair<int, int>> stack{{x0, y0}}, pixels;
            label[size_t(y0) * w + x0] = count;
            while (!stack.empty()) {
                const auto [x, y] = stack.back();
                stack.pop_back();
                pixels.push_back({x, y});
                const int nx[4] = {x + 1, x - 1, x, x}, ny[4] = {y, y, y + 1, y - 1};
                for (int i = 0; i < 4; ++i)
                    if (nx[i] >= 0 && nx[i] < w && ny[i] >= 0 && ny[i] < h &&
                        label[size_t(ny[i]) * w + nx[i]] < 0 && clipped(nx[i], ny[i])) {
                        label[size_t(ny[i]) * w + nx[i]] = count;
                        stack.push_back({nx[i], ny[i]});
                    }
            }
            ++count;
            double lum = 0, u = 0, v = 0;
            std::vector<double> zs;
            Vec3d power(0.0, 0.0, 0.0);
            for (const auto& [x, y] : pixels) {
                const float* t = truth.at(x, y);
                const double z = depth.at(x, y)[0];
                lum += rec709Luminance(t);
                u += x + 0.5;
                v += y + 0.5;
                zs.push_back(z);
                const double area = (z / camera.fx) * (z / camera.fy);
                power += Vec3d(t[0], t[1], t[2]) * area;
            }
            const double n = double(pixels.size());
            if (lum / n < 2.0) continue;
            std::nth_element(zs.begin(), zs.begin() + zs.size() / 2, zs.end());
            const double z = zs[zs.size() / 2];
            u /= n;
            v /= n;
            const double rho = std::sqrt(n / M_PI) * z / camera.fx;
            for (double c : {(u - camera.cx) / camera.fx * z, (v - camera.cy) / camera.fy * z, z})
                pos.push_back(float(c));
            radius.push_back(float(std::max(rho / 2, 0.03)));
            for (int c = 0; c < 3; ++c) rad.push_back(float(power[c]));
        }
    Emitters e;
    const int64_t k = int64_t(radius.size());
    if (k == 0) return e;
    e.position = torch::tensor(pos).reshape({k, 3});
    e.radius = torch::tensor(radius);
    e.alpha = torch::full({k}, 0.95f);
    e.radiance = torch::ones({k, 3});
    const auto perUnit = emitterIntensity(e, layout, pruneAlpha);  // J per unit radiance
    e.radiance = torch::tensor(rad).reshape({k, 3}) / perUnit.clamp_min(1e-9);
    std::fprintf(stderr, "analysis: %lld observed lamp blobs\n", (long long)k);
    return e;
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
    PairInputs inputs = makePairInputs(pair.ref, pair.src, cams.ref, *cams.src, result.range.near,
                                       result.range.far, config, impl_->device);
    inputs.collapseClipped = impl_->collapseClipped;
    inputs.injectAfterCompletion = std::getenv("LH_INJECT_AFTER") != nullptr;
    inputs.clippedAtBorderDepth = std::getenv("LH_BORDER_DEPTH") != nullptr;
    if (const char* depth = std::getenv("LH_CLIPPED_DEPTH"))
        inputs.clippedDepth =
            imageToTensor(resizeImage(readImage(depth), config.width, config.height))
                .narrow(1, 0, 1)
                .to(impl_->device);
    if (!impl_->clippedRadianceFrom.empty())
        inputs.clippedRadiance = imageToTensor(resizeImage(readImage(impl_->clippedRadianceFrom),
                                                           config.width, config.height))
                                     .to(impl_->device);
    torch::NoGradGuard noGrad;
    PipelineOutput out = impl_->net->run(inputs, true);
    if (const char* truthPath = std::getenv("LH_BLOB_TRUTH")) {
        const Emitters blobs = observedLampBlobs(pair.ref, readImage(truthPath),
                                                 readImage(std::getenv("LH_BLOB_DEPTH")), cams.ref,
                                                 inputs.layout, impl_->pruneAlpha);
        if (blobs.position.defined()) {
            Emitters onDevice = blobs;
            for (auto* t :
                 {&onDevice.position, &onDevice.radius, &onDevice.alpha, &onDevice.radiance})
                *t = t->to(impl_->device);
            out.cubes = addEmitters(out.cubes, onDevice, inputs.layout);
        }
    }
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
