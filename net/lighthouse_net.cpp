#include "net/lighthouse_net.h"

#include "core/atomic_file.h"
#include "core/errors.h"
#include "image/resample.h"
#include "net/hdr.h"
#include "net/height_profile.h"
#include "net/mpi_resample.h"
#include "net/psv.h"
#include "net/tensor_image.h"
#include "vdb/mpi.h"

#include <filesystem>
#include <fstream>

namespace lh::net {

namespace F = torch::nn::functional;

namespace {

// Input channels of the 2D MPI network for D planes: the reference image (3), the source
// image warped onto every plane (3 D), and every plane's photo-consistency cost (D): the mean
// absolute difference between the reference and the warped source.
int mpi2dInputChannels(int planes) { return 3 + 4 * planes; }
// Outputs: per plane an alpha and a blend-weight logit (2 D), then per pixel a background
// colour (3) and the brightening of clipped photo pixels (1).
int mpi2dOutputChannels(int planes) { return 2 * planes + 4; }

}  // namespace

LighthouseNetImpl::LighthouseNetImpl(const NetConfig& c) : config(c) {
    config.validate();
    if (c.mpiNetwork == "2d")
        mpiNet2d = register_module("mpi_net2d", UNet2d(mpi2dInputChannels(c.planes),
                                                       mpi2dOutputChannels(c.planes), c.mpiWidth));
    else
        mpiNet = register_module("mpi_net", UNet3d(6, c.hdr ? 6 : 5, c.baseWidth));
    // The 2D (standard) design also gives the completion networks voxel positions (3 channels).
    const int positionChannels = c.mpiNetwork == "2d" ? 3 : 0;
    const int profileChannels = c.heightProfile ? kHeightProfileChannels : 0;
    for (int k = 0; k < c.levels; ++k)
        completion.push_back(register_module(
            "completion" + std::to_string(k),
            UNet3d((k == 0 ? 4 : 8) + positionChannels + profileChannels, 5, c.baseWidth)));
    if (c.emitters > 0)
        emitterHead = register_module(
            "emitter_head",
            EmitterHead(c.emitters, c.emitterPhoto, c.emitterPhotoCells, c.emitterApart));
}

torch::Tensor LighthouseNetImpl::logColourAnchor(const torch::Tensor& refLinear) const {
    if (!config.colourAnchor) return {};
    return torch::log(refLinear.mean({2, 3}).clamp_min(1e-3)).reshape({1, 3, 1, 1, 1});
}

namespace {

// An invented colour from its logit: HDR (relative to the anchor when there is one) or sigmoid.
torch::Tensor inventedColour(const torch::Tensor& logit, bool hdr, const torch::Tensor& logAnchor) {
    if (!hdr) return torch::sigmoid(logit);
    return hdrActivation(logAnchor.defined() ? logit + logAnchor : logit);
}

}  // namespace

torch::Tensor LighthouseNetImpl::predictMpi(const torch::Tensor& psv,
                                            const torch::Tensor& refLinear,
                                            const torch::Tensor& logAnchor) {
    const int64_t d = psv.size(2), h = psv.size(3), w = psv.size(4);
    torch::Tensor background, weight, alpha, boost;  // [1, 3|1, D|1, H, W]
    if (mpiNet2d) {
        const auto ref = psv.select(2, 0).narrow(1, 0, 3);            // [1, 3, H, W]
        const auto warped = psv.narrow(1, 3, 3);                      // [1, 3, D, H, W]
        const auto cost = (warped - ref.unsqueeze(2)).abs().mean(1);  // [1, D, H, W]
        const auto input = torch::cat({ref, warped.reshape({1, 3 * d, h, w}), cost}, 1);
        const auto out = mpiNet2d(input);  // [1, 2D + 4, H, W]
        alpha = torch::sigmoid(out.narrow(1, 0, d)).unsqueeze(1);
        weight = torch::sigmoid(out.narrow(1, d, d)).unsqueeze(1);
        const auto bgLogit = out.narrow(1, 2 * d, 3).unsqueeze(2);
        background = inventedColour(bgLogit, config.hdr, logAnchor);
        boost = out.narrow(1, 2 * d + 3, 1).unsqueeze(2);
    } else {
        const auto out = mpiNet(psv);  // [1, 5 or 6, D, H, W]
        // Background = mean over planes; blend weight picks reference or background per plane.
        const auto bgLogit = out.narrow(1, 0, 3);
        background = inventedColour(bgLogit, config.hdr, logAnchor).mean(2, /*keepdim=*/true);
        weight = torch::sigmoid(out.narrow(1, 3, 1));
        alpha = torch::sigmoid(out.narrow(1, 4, 1));
        if (config.hdr) boost = out.narrow(1, 5, 1).mean(2, /*keepdim=*/true);
    }
    auto refColour = refLinear.unsqueeze(2);  // [1, 3, 1, H, W]
    // Where the photo clipped (lamps, windows) the truth is brighter than 1: the network may
    // scale those pixels up by exp(softplus(boost)), and only those.
    if (config.hdr)
        refColour =
            refColour * torch::exp(saturationWeight(refLinear).unsqueeze(2) * F::softplus(boost));
    const auto rgb = weight * refColour + (1.0 - weight) * background;
    return torch::cat({rgb, alpha}, 1);
}

torch::Tensor cropCoarserLevel(const torch::Tensor& coarser, int coarserLevel) {
    const int64_t r = coarser.size(2);
    // Level k covers the middle half of level k-1 in x and y, and in z the front half of
    // level 0 (centred on the camera) or the back half of a level >= 1 (camera on its back face).
    const int64_t z0 = coarserLevel == 0 ? r / 2 : 0;
    const auto crop = coarser.narrow(2, z0, r / 2).narrow(3, r / 4, r / 2).narrow(4, r / 4, r / 2);
    return crop.repeat_interleave(2, 2).repeat_interleave(2, 3).repeat_interleave(2, 4);
}

namespace {

// A cube [1, 4k, R, R, R] of (rgb, alpha) groups as network features: HDR colours as
// ln(1 + x), and at half resolution averaged in 2^3 blocks (colour weighted by alpha, so
// that empty voxels do not darken the surfaces beside them).
torch::Tensor completionFeatures(const torch::Tensor& cube, bool hdr, bool halve) {
    std::vector<torch::Tensor> groups;
    for (int64_t g = 0; g < cube.size(1) / 4; ++g) {
        auto rgb = cube.narrow(1, 4 * g, 3), alpha = cube.narrow(1, 4 * g + 3, 1);
        if (halve) {
            const auto a = F::avg_pool3d(alpha, F::AvgPool3dFuncOptions(2));
            rgb = F::avg_pool3d(rgb * alpha, F::AvgPool3dFuncOptions(2)) / a.clamp_min(1e-4);
            alpha = a;
        }
        groups.push_back(hdr ? radianceFeature(rgb) : rgb);
        groups.push_back(alpha);
    }
    return torch::cat(groups, 1);
}

}  // namespace

std::vector<torch::Tensor> LighthouseNetImpl::complete(const std::vector<torch::Tensor>& inputs,
                                                       const VolumeLayout& layout,
                                                       const torch::Tensor& logAnchor) {
    std::vector<torch::Tensor> out;
    const bool halve = config.completionScale == 2;
    const VolumeLayout networkLayout{layout.s0, layout.levels, config.completionResolution()};
    // Level 0 holds the whole room: its profile serves every level.
    const torch::Tensor profile = config.heightProfile ? heightProfile(inputs[0]) : torch::Tensor();
    for (size_t k = 0; k < inputs.size(); ++k) {
        const auto input =
            k == 0 ? inputs[k]
                   : torch::cat({inputs[k], cropCoarserLevel(out.back(), int(k) - 1)}, 1);
        auto features = completionFeatures(input, config.hdr, halve);
        if (config.mpiNetwork == "2d") {
            constexpr double kPositionUnit = 4.0;  // metres
            const auto positions = (voxelCentres(networkLayout, int(k)) / kPositionUnit)
                                       .permute({3, 0, 1, 2})
                                       .unsqueeze(0)
                                       .to(features.device(), torch::kFloat32);
            features = torch::cat({features, positions}, 1);
        }
        if (profile.defined())
            features = torch::cat(
                {features, heightProfileFeatures(profile, layout, int(k),
                                                 config.completionResolution(), config.hdr)},
                1);
        auto raw = completion[k](features);  // [1, 5, r, r, r]
        if (halve)
            raw = F::interpolate(
                raw, F::InterpolateFuncOptions()
                         .size(std::vector<int64_t>{inputs[k].size(2), inputs[k].size(3),
                                                    inputs[k].size(4)})
                         .mode(torch::kTrilinear)
                         .align_corners(false));
        const auto colourLogit = raw.narrow(1, 0, 3);
        const auto colour = inventedColour(colourLogit, config.hdr, logAnchor);
        const auto predicted = torch::cat({colour, torch::sigmoid(raw.narrow(1, 3, 1))}, 1);
        const auto weight = torch::sigmoid(raw.narrow(1, 4, 1));
        out.push_back(weight * predicted + (1.0 - weight) * inputs[k]);
    }
    return out;
}

PipelineOutput LighthouseNetImpl::run(const PairInputs& in, bool runCompletion) {
    PipelineOutput result;
    const auto psv = planeSweepVolume(in.refEncoded, in.srcEncoded, in.ref, in.src, in.depths);
    const auto logAnchor = logColourAnchor(in.refLinear);
    result.mpi = predictMpi(psv, in.refLinear, logAnchor);
    for (int k = 0; k < in.layout.levels; ++k)
        result.mpiCubes.push_back(resampleMpiToLevel(result.mpi, in.depths, in.ref, in.layout, k,
                                                     config.hdr ? kMaxMpiRadiance : 1.0));
    if (runCompletion) result.cubes = complete(result.mpiCubes, in.layout, logAnchor);
    if (runCompletion && emitterHead) {
        const auto photoLuminance = luminanceTensor(in.refLinear).mean().clamp_min(1e-3);
        const auto& photo = config.emitterPhotoUnclipped && in.refUnclipped.defined()
                                ? in.refUnclipped
                                : in.refLinear;
        result.emitters = emitterHead(result.cubes[0], in.layout, photoLuminance, photo);
        result.cubes = addEmitters(result.cubes, result.emitters, in.layout);
    }
    return result;
}

torch::Tensor photoRadianceTensor(const ImageRGB& photo, int width, int height) {
    return torch::nan_to_num(imageToTensor(resizeImage(photo, width, height)), 0.0,
                             kMaxPhotoRadiance, 0.0)
        .clamp_min(0);
}

PairInputs makePairInputs(const ImageRGB& ref, const ImageRGB& src, const PinholeCamera& refCamera,
                          const PinholeCamera& srcCamera, double near, double far,
                          const NetConfig& config, const torch::Device& device) {
    PairInputs in;
    in.ref = refCamera.resized(config.width, config.height);
    in.src = srcCamera.resized(config.width, config.height);
    // A linear EXR photo keeps radiance above 1, which no network but a photo head that reads
    // it (NetConfig::emitterPhotoUnclipped) saw in training: the rest reads it clipped at 1, as
    // a camera would have saved it.
    const auto refUnclipped = photoRadianceTensor(ref, config.width, config.height);
    const auto refLinear = refUnclipped.clamp_max(1.0);
    const auto srcLinear = imageToTensor(resizeImage(src, config.width, config.height));
    in.refUnclipped = refUnclipped.to(device);
    in.refLinear = refLinear.to(device);
    in.refEncoded = srgbEncodeTensor(refLinear).to(device);
    in.srcEncoded = srgbEncodeTensor(srcLinear).to(device);
    in.depths = disparityLinearDepths(near, far, config.planes);
    in.layout = VolumeLayout::fromFarDepth(far, config.levels, config.resolution);
    return in;
}

void copyWeights(LighthouseNet& to, LighthouseNet& from) {
    torch::NoGradGuard noGrad;
    const auto parameters = from->named_parameters();
    for (auto& p : to->named_parameters()) p.value().copy_(parameters[p.key()]);
    const auto buffers = from->named_buffers();
    for (auto& b : to->named_buffers()) b.value().copy_(buffers[b.key()]);
}

namespace {

// Whether `to` is a network's first convolution (its stem) with more input channels than
// `from` (dimension 1) and the same sizes elsewhere. Only stems: a deeper convolution with more
// inputs belongs to a wider network, whose extra inputs are not new information.
bool gainsInputChannels(const std::string& name, const torch::Tensor& to,
                        const torch::Tensor& from) {
    const std::string stem = ".stem.weight";
    if (name.size() < stem.size() ||
        name.compare(name.size() - stem.size(), stem.size(), stem) != 0)
        return false;
    if (to.dim() < 2 || to.dim() != from.dim() || to.size(1) <= from.size(1)) return false;
    for (int64_t d = 0; d < to.dim(); ++d)
        if (d != 1 && to.size(d) != from.size(d)) return false;
    return true;
}

}  // namespace

MatchedWeights copyMatchingWeights(LighthouseNet& to, LighthouseNet& from) {
    torch::NoGradGuard noGrad;
    MatchedWeights m;
    const auto copy = [&m](const torch::OrderedDict<std::string, torch::Tensor>& source,
                           torch::OrderedDict<std::string, torch::Tensor> target) {
        for (auto& t : target) {
            ++m.tensors;
            m.values += t.value().numel();
            const torch::Tensor* s = source.find(t.key());
            if (!s) continue;
            if (s->sizes().equals(t.value().sizes())) {
                t.value().copy_(*s);
            } else if (gainsInputChannels(t.key(), t.value(), *s)) {
                // A convolution that reads more inputs (a completion network's stem, given the
                // height profile): the old inputs keep their weights, the new ones start at
                // zero, so the network computes what it did until training uses them.
                t.value().zero_();
                t.value().narrow(1, 0, s->size(1)).copy_(*s);
                ++m.extended;
            } else {
                continue;
            }
            ++m.copied;
            m.copiedValues += t.value().numel();
        }
    };
    copy(from->named_parameters(), to->named_parameters());
    copy(from->named_buffers(), to->named_buffers());
    return m;
}

void saveModel(LighthouseNet& net, const std::string& path, bool halfPrecision) {
    torch::serialize::OutputArchive archive;
    archive.write("lighthouse_config", c10::IValue(net->config.toJson()));
    archive.write("lighthouse_model_version", c10::IValue(int64_t(2)));
    archive.write("lighthouse_half_precision", c10::IValue(halfPrecision));
    if (halfPrecision) {
        // A copy in half precision: the caller's network (still training, perhaps) keeps float32.
        LighthouseNet copy(net->config);
        copyWeights(copy, net);
        copy->to(torch::kCPU, torch::kHalf);
        copy->save(archive);
    } else {
        net->save(archive);
    }
    // Through a stream: save_to(file) names the zip's root folder after the file, and the
    // temporary's name holds the writer's pid, so the same weights gave different bytes.
    // From a stream the root is always "archive": equal models are equal files.
    AtomicOutput out(path);  // a kill mid-write leaves the previous file whole
    {
        std::ofstream file(out.tempPath(), std::ios::binary);
        archive.save_to(file);
        file.flush();
        if (!file) throw FileError("could not write the model '" + path + "' (disk full?)");
    }
    out.commit();
}

LighthouseNet loadModel(const std::string& path, const torch::Device& device) {
    if (!std::filesystem::is_regular_file(path))
        throw FileError("model file '" + path +
                        "' not found (train one with 'lighthouse train', or omit --model to use "
                        "the bundled one)");
    torch::serialize::InputArchive archive;
    c10::IValue configValue;
    try {
        archive.load_from(path);
        if (!archive.try_read("lighthouse_config", configValue) || !configValue.isString())
            throw FileError("'" + path + "' is not a Lighthouse model (no configuration inside)");
    } catch (const c10::Error& e) {
        throw FileError("'" + path + "' is not a readable model file: " +
                        std::string(e.what_without_backtrace()));
    }
    LighthouseNet net(NetConfig::fromJson(configValue.toStringRef(), path));
    c10::IValue halfValue;
    // Parameters are read into tensors of the file's type, then computed in float.
    if (archive.try_read("lighthouse_half_precision", halfValue) && halfValue.isBool() &&
        halfValue.toBool())
        net->to(torch::kCPU, torch::kHalf);
    try {
        net->load(archive);
    } catch (const c10::Error& e) {
        throw FileError("'" + path + "' does not match its configuration: " +
                        std::string(e.what_without_backtrace()));
    }
    net->to(device, torch::kFloat32);  // half-precision files are computed in float
    net->eval();
    return net;
}

}  // namespace lh::net
