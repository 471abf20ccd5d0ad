#include "net/lighthouse_net.h"

#include "core/atomic_file.h"
#include "core/errors.h"
#include "net/mpi_resample.h"
#include "net/psv.h"
#include "net/tensor_image.h"
#include "render/contact_sheet.h"
#include "vdb/mpi.h"

#include <filesystem>

namespace lh::net {

LighthouseNetImpl::LighthouseNetImpl(const NetConfig& c) : config(c) {
    config.validate();
    mpiNet = register_module("mpi_net", UNet3d(6, 5, c.baseWidth));
    for (int k = 0; k < c.levels; ++k)
        completion.push_back(
            register_module("completion" + std::to_string(k), UNet3d(k == 0 ? 4 : 8, 5, c.baseWidth)));
}

torch::Tensor LighthouseNetImpl::predictMpi(const torch::Tensor& psv, const torch::Tensor& refLinear) {
    const auto out = mpiNet(psv);  // [1, 5, D, H, W]
    // Background = mean over planes; blend weight picks reference or background per plane.
    const auto background = torch::sigmoid(out.narrow(1, 0, 3)).mean(2, /*keepdim=*/true);
    const auto weight = torch::sigmoid(out.narrow(1, 3, 1));
    const auto alpha = torch::sigmoid(out.narrow(1, 4, 1));
    const auto rgb = weight * refLinear.unsqueeze(2) + (1.0 - weight) * background;
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

std::vector<torch::Tensor> LighthouseNetImpl::complete(const std::vector<torch::Tensor>& inputs) {
    std::vector<torch::Tensor> out;
    for (size_t k = 0; k < inputs.size(); ++k) {
        const auto input = k == 0 ? inputs[k] : torch::cat({inputs[k], cropCoarserLevel(out.back(), int(k) - 1)}, 1);
        const auto raw = completion[k](input);
        const auto predicted = torch::sigmoid(raw.narrow(1, 0, 4));
        const auto weight = torch::sigmoid(raw.narrow(1, 4, 1));
        out.push_back(weight * predicted + (1.0 - weight) * inputs[k]);
    }
    return out;
}

PipelineOutput LighthouseNetImpl::run(const PairInputs& in, bool runCompletion) {
    PipelineOutput result;
    const auto psv = planeSweepVolume(in.refEncoded, in.srcEncoded, in.ref, in.src, in.depths);
    result.mpi = predictMpi(psv, in.refLinear);
    for (int k = 0; k < in.layout.levels; ++k)
        result.mpiCubes.push_back(resampleMpiToLevel(result.mpi, in.depths, in.ref, in.layout, k));
    if (runCompletion) result.cubes = complete(result.mpiCubes);
    return result;
}

PairInputs makePairInputs(const ImageRGB& ref, const ImageRGB& src, const PinholeCamera& refCamera,
                          const PinholeCamera& srcCamera, double near, double far, const NetConfig& config,
                          const torch::Device& device) {
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

void saveModel(LighthouseNet& net, const std::string& path) {
    torch::serialize::OutputArchive archive;
    archive.write("lighthouse_config", c10::IValue(net->config.toJson()));
    archive.write("lighthouse_model_version", c10::IValue(int64_t(1)));
    net->save(archive);
    const std::string temporary = path + ".partial";
    archive.save_to(temporary);
    std::filesystem::rename(temporary, path);
}

LighthouseNet loadModel(const std::string& path, const torch::Device& device) {
    if (!std::filesystem::is_regular_file(path))
        throw FileError("model file '" + path + "' not found (train one with 'lighthouse train', or omit --model to use the bundled one)");
    torch::serialize::InputArchive archive;
    c10::IValue configValue;
    try {
        archive.load_from(path);
        if (!archive.try_read("lighthouse_config", configValue) || !configValue.isString())
            throw FileError("'" + path + "' is not a Lighthouse model (no configuration inside)");
    } catch (const c10::Error& e) {
        throw FileError("'" + path + "' is not a readable model file: " + std::string(e.what_without_backtrace()));
    }
    LighthouseNet net(NetConfig::fromJson(configValue.toStringRef(), path));
    try {
        net->load(archive);
    } catch (const c10::Error& e) {
        throw FileError("'" + path + "' does not match its configuration: " + std::string(e.what_without_backtrace()));
    }
    net->to(device);
    net->eval();
    return net;
}

}  // namespace lh::net
