#include "net/lighthouse_net.h"

#include <cstdlib>

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
    if (in.collapseClipped) result.mpi = collapseClippedMpiColumns(result.mpi, in.refLinear);
    if (in.clippedDepth.defined()) {
        // Each clipped column opaque on the plane nearest its true depth (in disparity).
        const auto clipped = (std::get<0>(in.refLinear.max(1, true)) >= 0.99).unsqueeze(2);
        std::vector<float> inverse;
        for (double d : in.depths) inverse.push_back(float(1.0 / d));
        const auto planes = torch::tensor(inverse).to(result.mpi.device()).view({1, 1, -1, 1, 1});
        const auto truth = (1.0 / in.clippedDepth.clamp_min(1e-3)).unsqueeze(2);
        const auto nearest = (planes - truth).abs().argmin(2, true);
        const auto alpha = result.mpi.narrow(1, 3, 1);
        const auto onPlane = torch::zeros_like(alpha).scatter_(2, nearest, 1.0);
        const auto colour = result.mpi.narrow(1, 0, 3);
        // The column's colour as the camera sees it, on every plane.
        const auto clear = (1 - alpha).flip({2});
        const auto inFront = torch::cat({torch::ones_like(clear.narrow(2, 0, 1)),
                                         torch::cumprod(clear, 2).narrow(2, 0, clear.size(2) - 1)},
                                        2)
                                 .flip({2});
        const auto weight = alpha * inFront;
        const auto seen = (colour * weight).sum(2, true) / weight.sum(2, true).clamp_min(1e-6);
        const auto newMpi = torch::cat({seen.expand_as(colour), onPlane}, 1);
        result.mpi = torch::where(clipped.expand_as(result.mpi), newMpi, result.mpi);
    }
    if (in.clippedAtBorderDepth)
        result.mpi = clippedAtBorderDepth(result.mpi, in.refLinear, in.depths);
    if (std::getenv("LH_CLEAR_CLIPPED")) {
        // Analysis: the clipped columns emptied (alpha 0), so nothing the MPI drew there stands
        // in front of an observed-lamp blob.
        const auto clipped = (std::get<0>(in.refLinear.max(1, true)) >= 0.99).unsqueeze(2);
        const auto alpha = result.mpi.narrow(1, 3, 1);
        result.mpi = torch::cat(
            {result.mpi.narrow(1, 0, 3), torch::where(clipped, torch::zeros_like(alpha), alpha)},
            1);
    }
    torch::Tensor clippedMpi = result.mpi;
    if (in.clippedRadiance.defined()) {
        const auto clipped = (std::get<0>(in.refLinear.max(1, true)) >= 0.99).unsqueeze(2);
        const auto truth = in.clippedRadiance.unsqueeze(2).expand_as(result.mpi.narrow(1, 0, 3));
        result.mpi =
            torch::cat({torch::where(clipped.expand_as(truth), truth, result.mpi.narrow(1, 0, 3)),
                        result.mpi.narrow(1, 3, 1)},
                       1);
    }
    for (int k = 0; k < in.layout.levels; ++k)
        result.mpiCubes.push_back(resampleMpiToLevel(result.mpi, in.depths, in.ref, in.layout, k,
                                                     config.hdr ? kMaxMpiRadiance : 1.0));
    if (runCompletion && in.injectAfterCompletion && in.clippedRadiance.defined()) {
        std::vector<torch::Tensor> clippedCubes;
        for (int k = 0; k < in.layout.levels; ++k)
            clippedCubes.push_back(resampleMpiToLevel(clippedMpi, in.depths, in.ref, in.layout, k,
                                                      config.hdr ? kMaxMpiRadiance : 1.0));
        result.cubes = complete(clippedCubes, in.layout, logAnchor);
        for (int k = 0; k < in.layout.levels; ++k) {
            const auto excess = (result.mpiCubes[k] - clippedCubes[k]).narrow(1, 0, 3);
            result.cubes[k] = torch::cat({(result.cubes[k].narrow(1, 0, 3) + excess).clamp_min(0),
                                          result.cubes[k].narrow(1, 3, 1)},
                                         1);
        }
    } else if (runCompletion)
        result.cubes = complete(result.mpiCubes, in.layout, logAnchor);
    if (runCompletion && emitterHead) {
        const auto photoLuminance = luminanceTensor(in.refLinear).mean().clamp_min(1e-3);
        result.emitters = emitterHead(result.cubes[0], in.layout, photoLuminance, in.refLinear);
        result.cubes = addEmitters(result.cubes, result.emitters, in.layout);
    }
    return result;
}

torch::Tensor collapseClippedMpiColumns(const torch::Tensor& mpi, const torch::Tensor& refLinear) {
    const auto colour = mpi.narrow(1, 0, 3), alpha = mpi.narrow(1, 3, 1);  // [1, 1, D, H, W]
    // Transmittance in front of each plane (the nearer planes come later along D).
    const auto clear = (1 - alpha).flip({2});
    const auto inFront = torch::cat({torch::ones_like(clear.narrow(2, 0, 1)),
                                     torch::cumprod(clear, 2).narrow(2, 0, clear.size(2) - 1)},
                                    2)
                             .flip({2});
    const auto weight = alpha * inFront;  // each plane's share of the pixel
    const auto total = weight.sum(2, true);
    const auto composited = (colour * weight).sum(2, true) / total.clamp_min(1e-6);
    const auto strongest = weight.argmax(2, true);
    const auto onPlane = torch::zeros_like(alpha).scatter_(2, strongest, torch::ones_like(total));
    const auto collapsed = torch::cat({composited.expand_as(colour), onPlane * total}, 1);
    const auto clipped =
        (std::get<0>(refLinear.max(1, true)) >= 0.99).unsqueeze(2).expand_as(alpha);  // [1,1,D,H,W]
    return torch::where(clipped.expand_as(mpi), collapsed, mpi);
}

torch::Tensor clippedAtBorderDepth(const torch::Tensor& mpi, const torch::Tensor& refLinear,
                                   const std::vector<double>& depths) {
    namespace F = torch::nn::functional;
    const auto colour = mpi.narrow(1, 0, 3), alpha = mpi.narrow(1, 3, 1);  // [1, 1, D, H, W]
    const auto clear = (1 - alpha).flip({2});
    const auto inFront = torch::cat({torch::ones_like(clear.narrow(2, 0, 1)),
                                     torch::cumprod(clear, 2).narrow(2, 0, clear.size(2) - 1)},
                                    2)
                             .flip({2});
    const auto weight = alpha * inFront;
    const auto total = weight.sum(2, true).clamp_min(1e-6);
    std::vector<float> inverse;
    for (double d : depths) inverse.push_back(float(1.0 / d));
    const auto planes = torch::tensor(inverse).to(mpi.device()).view({1, 1, -1, 1, 1});
    auto disparity = ((weight * planes).sum(2, true) / total).squeeze(2);  // [1, 1, H, W]
    const auto clipped = std::get<0>(refLinear.max(1, true)) >= 0.99;      // [1, 1, H, W]
    if (!clipped.any().item<bool>()) return mpi;
    // Fill the clipped pixels' disparity inward from their unclipped borders.
    auto known = (~clipped).to(torch::kFloat);
    disparity = disparity * known;
    const auto pool = F::AvgPool2dFuncOptions(3).stride(1).padding(1);
    for (int step = 0; step < refLinear.size(2) + refLinear.size(3); ++step) {
        const auto den = F::avg_pool2d(known, pool);
        const auto num = F::avg_pool2d(disparity * known, pool);
        const auto reached = (known < 0.5) & (den > 0);
        if (!reached.any().item<bool>()) break;
        disparity = torch::where(reached, num / den.clamp_min(1e-9), disparity);
        known = torch::where(reached, torch::ones_like(known), known);
    }
    const auto nearest = (planes - disparity.unsqueeze(2)).abs().argmin(2, true);
    const auto onPlane = torch::zeros_like(alpha).scatter_(2, nearest, 1.0);
    const auto seen = (colour * weight).sum(2, true) / total;
    const auto moved = torch::cat({seen.expand_as(colour), onPlane}, 1);
    return torch::where(clipped.unsqueeze(2).expand_as(mpi), moved, mpi);
}

PairInputs makePairInputs(const ImageRGB& ref, const ImageRGB& src, const PinholeCamera& refCamera,
                          const PinholeCamera& srcCamera, double near, double far,
                          const NetConfig& config, const torch::Device& device) {
    PairInputs in;
    in.ref = refCamera.resized(config.width, config.height);
    in.src = srcCamera.resized(config.width, config.height);
    const auto refLinear = imageToTensor(resizeImage(ref, config.width, config.height));
    const auto srcLinear = imageToTensor(resizeImage(src, config.width, config.height));
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
