#include "net/widen.h"

#include "core/errors.h"

#include <string>

namespace lh::net {

namespace {

// For each channel of the wide network: the narrow channel it copies, and, in a widened map
// (every channel a copy), which of the two copies it is (+1 first, -1 second).
struct ChannelMap {
    std::vector<int64_t> source;
    std::vector<float> copySign;  // empty unless widened
    bool widened = false;

    static ChannelMap same(int64_t n) {
        ChannelMap m;
        for (int64_t i = 0; i < n; ++i) m.source.push_back(i);
        return m;
    }
    // [a, a] for a block of `n` narrow channels starting at `offset`, appended.
    void appendDoubled(int64_t n, int64_t offset) {
        widened = true;
        for (int copy = 0; copy < 2; ++copy)
            for (int64_t i = 0; i < n; ++i)
                source.push_back(offset + i), copySign.push_back(copy == 0 ? 1.f : -1.f);
    }
    static ChannelMap doubled(int64_t n) {
        ChannelMap m;
        m.appendDoubled(n, 0);
        return m;
    }
    // The decoder's concatenation [upsampled (a channels), skip (b channels)], widened.
    static ChannelMap concatenation(int64_t a, int64_t b) {
        ChannelMap m;
        m.appendDoubled(a, 0);
        m.appendDoubled(b, a);
        return m;
    }
    torch::Tensor index(const torch::Device& device) const {
        return torch::tensor(source, torch::kLong).to(device);
    }
    torch::Tensor signs(const torch::Device& device) const {
        return torch::tensor(copySign, torch::kFloat32).to(device);
    }
};

void requireShape(const torch::Tensor& t, const std::vector<int64_t>& shape,
                  const std::string& name) {
    if (!t.sizes().equals(shape))
        throw InputError("cannot widen: '" + name + "' has shape " + c10::str(t.sizes()) +
                         ", expected " + c10::str(shape));
}

// Writes into `wide` the convolution `narrow` widened by `out` and `in` (5D weight + bias).
void widenConvolution(torch::Tensor wideWeight, torch::Tensor wideBias,
                      const torch::Tensor& narrowWeight, const torch::Tensor& narrowBias,
                      const ChannelMap& out, const ChannelMap& in, double split,
                      const std::string& name) {
    std::vector<int64_t> shape = wideWeight.sizes().vec();
    shape[0] = int64_t(out.source.size());
    shape[1] = int64_t(in.source.size());
    requireShape(wideWeight, shape, name + ".weight");
    const torch::Device device = narrowWeight.device();
    auto weight = narrowWeight.index_select(0, out.index(device)).index_select(1, in.index(device));
    if (in.widened) {
        // d per (wide output, narrow input, tap), shared by the two copies of that input.
        auto d = (torch::rand({shape[0], narrowWeight.size(1), shape[2], shape[3], shape[4]},
                              narrowWeight.options()) *
                      2.0 -
                  1.0) *
                 split;
        d = d.index_select(1, in.index(device)) * in.signs(device).view({1, -1, 1, 1, 1});
        weight = weight * (0.5 + d);
    }
    wideWeight.copy_(weight);
    requireShape(wideBias, {shape[0]}, name + ".bias");
    wideBias.copy_(narrowBias.index_select(0, out.index(device)));
}

}  // namespace

void widenUNet3d(UNet3d& wide, const UNet3d& narrow, int w, double split) {
    torch::NoGradGuard noGrad;
    const UNet3dWidths widths = unet3dWidths(w);
    const int* enc = widths.encoder;
    const int* dec = widths.decoder;
    const auto norm = [](ChannelLayerNorm& to, const ChannelLayerNorm& from, const ChannelMap& m,
                         const std::string& name) {
        requireShape(to->gain, {int64_t(m.source.size())}, name + ".gain");
        const torch::Device device = from->gain.device();
        to->gain.copy_(from->gain.index_select(0, m.index(device)));
        to->bias.copy_(from->bias.index_select(0, m.index(device)));
    };
    const auto preAct = [&](PreActConv& to, const PreActConv& from, const ChannelMap& out,
                            const ChannelMap& in, const std::string& name) {
        norm(to->norm, from->norm, in, name + ".norm");
        widenConvolution(to->conv->weight, to->conv->bias, from->conv->weight, from->conv->bias,
                         out, in, split, name + ".conv");
    };
    const auto residual = [&](ResidualPair& to, const ResidualPair& from, int64_t channels,
                              const std::string& name) {
        const ChannelMap m = ChannelMap::doubled(channels);
        preAct(to->first, from->first, m, m, name + ".first");
        preAct(to->second, from->second, m, m, name + ".second");
    };
    widenConvolution(wide->stem->weight, wide->stem->bias, narrow->stem->weight, narrow->stem->bias,
                     ChannelMap::doubled(enc[0]), ChannelMap::same(narrow->stem->weight.size(1)),
                     split, "stem");
    residual(wide->encRes[0], narrow->encRes[0], enc[0], "enc_res0");
    for (int s = 0; s < 4; ++s) {
        preAct(wide->down[s], narrow->down[s], ChannelMap::doubled(enc[s + 1]),
               ChannelMap::doubled(enc[s]), "down" + std::to_string(s));
        residual(wide->encRes[s + 1], narrow->encRes[s + 1], enc[s + 1],
                 "enc_res" + std::to_string(s + 1));
    }
    int64_t below = enc[4];
    for (int s = 0; s < 4; ++s) {
        preAct(wide->merge[s], narrow->merge[s], ChannelMap::doubled(dec[s]),
               ChannelMap::concatenation(below, enc[3 - s]), "merge" + std::to_string(s));
        residual(wide->decRes[s], narrow->decRes[s], dec[s], "dec_res" + std::to_string(s));
        below = dec[s];
    }
    preAct(wide->head, narrow->head, ChannelMap::same(narrow->head->conv->weight.size(0)),
           ChannelMap::doubled(below), "head");
}

void widenModel(LighthouseNet& wide, LighthouseNet& narrow, double split) {
    NetConfig doubled = narrow->config;
    doubled.baseWidth *= 2;
    if (!doubled.sameParameters(wide->config) || narrow->config.mpiNetwork != "2d")
        throw InputError("cannot widen a '" + narrow->config.name + "' model into a '" +
                         wide->config.name +
                         "' one: the configurations must differ only in a base width twice "
                         "as large, with the 2D MPI network (standard into wide)");
    copyMatchingWeights(wide, narrow);
    for (size_t k = 0; k < wide->completion.size(); ++k)
        widenUNet3d(wide->completion[k], narrow->completion[k], narrow->config.baseWidth, split);
}

}  // namespace lh::net
