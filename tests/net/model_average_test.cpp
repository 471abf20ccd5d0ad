// Averaging model files (net/model_average.h): known answers on tiny networks.
#include "net/model_average.h"

#include "core/errors.h"
#include "net/lighthouse_net.h"
#include "tests/net/net_test_scenes.h"
#include "tests/support/temp_path.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace lh::net {
namespace {

using test::tinyConfig;

// A tiny model whose every parameter holds `value`, written to a temporary file.
std::string constantModel(const NetConfig& config, float value, const std::string& name) {
    LighthouseNet net(config);
    torch::NoGradGuard noGrad;
    for (auto& p : net->parameters()) p.fill_(value);
    const std::string path = test::uniqueTempPath(name);
    saveModel(net, path);
    return path;
}

// The average of `inputs`, written and read back.
LighthouseNet averageOf(const std::vector<std::string>& inputs) {
    const std::string path = test::uniqueTempPath("lighthouse_average_out.pt");
    writeAveragedModel(inputs, path, false);
    LighthouseNet net = loadModel(path, torch::Device(torch::kCPU));
    std::filesystem::remove(path);
    return net;
}

TEST(ModelAverage, EveryParameterIsTheMeanOfTheModels) {
    const std::string a = constantModel(tinyConfig(), 1.0f, "lighthouse_average_a.pt");
    const std::string b = constantModel(tinyConfig(), 2.0f, "lighthouse_average_b.pt");
    const std::string c = constantModel(tinyConfig(), 6.0f, "lighthouse_average_c.pt");
    LighthouseNet two = averageOf({a, b});
    LighthouseNet three = averageOf({a, b, c});
    EXPECT_EQ(two->config.toJson(), tinyConfig().toJson());
    ASSERT_FALSE(three->parameters().empty());
    for (const auto& p : two->parameters())
        EXPECT_TRUE(torch::allclose(p, torch::full_like(p, 1.5f)));
    for (const auto& p : three->parameters())  // (1 + 2 + 6) / 3, not a running blend
        EXPECT_TRUE(torch::allclose(p, torch::full_like(p, 3.0f)));
    for (const auto& path : {a, b, c}) std::filesystem::remove(path);
}

// An average of one model with itself is that model: its predictions do not change.
TEST(ModelAverage, AModelAveragedWithItselfPredictsTheSame) {
    torch::manual_seed(5);
    LighthouseNet net(tinyConfig());
    const std::string a = test::uniqueTempPath("lighthouse_average_self.pt");
    saveModel(net, a);
    LighthouseNet average = averageOf({a, a});
    const auto original = net->named_parameters();
    for (const auto& p : average->named_parameters())
        EXPECT_TRUE(torch::allclose(p.value(), original[p.key()])) << p.key();
    std::filesystem::remove(a);
}

TEST(ModelAverage, RefusesOneModelAndModelsOfAnotherConfiguration) {
    const std::string a = constantModel(tinyConfig(), 1.0f, "lighthouse_average_one.pt");
    NetConfig pruned = tinyConfig();
    pruned.pruneAlpha = 0.2;
    const std::string b = constantModel(pruned, 1.0f, "lighthouse_average_pruned.pt");
    const std::string out = test::uniqueTempPath("lighthouse_average_refused.pt");
    EXPECT_THROW(writeAveragedModel({a}, out, false), InputError);
    try {
        writeAveragedModel({a, b}, out, false);
        ADD_FAILURE() << "models of two configurations were averaged";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(b), std::string::npos) << e.what();
    }
    // A model trained under a highlight gain is another configuration too: averaged with one
    // trained without it, the soup would have no one gain to record.
    NetConfig gained = tinyConfig();
    gained.highlightGain = 10.0;
    const std::string c = constantModel(gained, 1.0f, "lighthouse_average_gained.pt");
    EXPECT_THROW(writeAveragedModel({a, c}, out, false), InputError);
    std::filesystem::remove(c);
    EXPECT_THROW(writeAveragedModel({a, "/nonexistent/model.pt"}, out, false), FileError);
    EXPECT_FALSE(std::filesystem::exists(out));  // nothing written when refused
    std::filesystem::remove(a);
    std::filesystem::remove(b);
}

}  // namespace
}  // namespace lh::net
