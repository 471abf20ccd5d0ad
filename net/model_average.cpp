#include "net/model_average.h"

#include "core/errors.h"
#include "net/lighthouse_net.h"
#include "net/weight_average.h"

namespace lh::net {

void writeAveragedModel(const std::vector<std::string>& inputs, const std::string& output,
                        bool halfPrecision) {
    if (inputs.size() < 2)
        throw InputError("averaging needs two or more model files, got " +
                         std::to_string(inputs.size()));
    const torch::Device cpu(torch::kCPU);
    LighthouseNet average = loadModel(inputs[0], cpu);
    const std::string configuration = average->config.toJson();
    for (size_t k = 1; k < inputs.size(); ++k) {
        LighthouseNet next = loadModel(inputs[k], cpu);
        if (next->config.toJson() != configuration)
            throw InputError("'" + inputs[k] + "' has another configuration than '" + inputs[0] +
                             "' (architecture, pruning threshold or highlight gain): only "
                             "models fine-tuned from one model, with one configuration, can be "
                             "averaged");
        // The running mean of k + 1 models: the mean of the first k, weighted k / (k + 1).
        updateWeightAverage(average, next, double(k) / double(k + 1));
    }
    saveModel(average, output, halfPrecision);
}

}  // namespace lh::net
