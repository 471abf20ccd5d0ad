// Averaging the weights of several models (a "model soup", Wortsman et al. 2022): models
// fine-tuned from one starting model with different losses or seeds lie in one basin of the
// loss, and their weight average can score better than each of them, at the cost of one model
// (unlike an ensemble, which predicts with all of them). On the fine-tunes of this project's
// bundled model it scored within 0.05 dB of its models' mean (models/EXPERIMENTS.md, "model
// soups"). Torch-free: the CLI includes it.
#pragma once

#include <string>
#include <vector>

namespace lh::net {

// Writes to `output` (atomically; in half precision with `halfPrecision`) the uniform average
// of the parameters of the model files at `inputs` (two or more, each read as loadModel does).
// Every model must have the same configuration (the same architecture and the same pruning
// threshold): otherwise InputError, naming the first file that differs. Average only models
// fine-tuned from one starting point: the average of unrelated networks is not a network of
// either.
void writeAveragedModel(const std::vector<std::string>& inputs, const std::string& output,
                        bool halfPrecision);

}  // namespace lh::net
