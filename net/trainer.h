// `lighthouse train`: the paper's staged schedule, scaled to our budget (SPEC.md step 8).
//   stage 1 (first 25% of iterations): the MPI network alone, on the held-out view;
//   stage 2 (to 90%): the envmap loss added, training the completion networks and,
//            through the non-gradient-stopped blend, the MPI network;
//   stage 3 (last 10%): the PatchGAN adversarial loss added (weight 0.1).
// Image losses: the paper's VGG-19 perceptual loss with --vgg FILE, else the substitute of
// losses.h. Adam at --lr, divided by 10 for the last 20% (the paper's 1e-4 -> 1e-5); batch 1; non-finite
// gradients zeroed; gradients clipped to a global norm of 5.
#pragma once

#include <iosfwd>
#include <string>

namespace lh::net {

struct TrainOptions {
    std::string data;          // training split (lighthouse synth --split train)
    std::string validation;    // held-out scenes; empty: the last 5% of `data`, not trained on
    std::string config = "small";
    std::string out = "model.pt";  // model; the checkpoint is OUT.checkpoint, the log OUT.csv/.png
    int iterations = 12000;
    double learningRate = 3e-4;
    int validateEvery = 500;
    int validationScenes = 8;
    int checkpointEvery = 250;
    int logEvery = 25;
    unsigned long long seed = 1;
    std::string device = "cpu";
    int threads = 0;
    bool resume = true;        // continue from OUT.checkpoint when it exists
    std::string vggWeights;    // VGG-19 weights (net/vgg_loss.h): the paper's perceptual loss
                               // instead of the substitute

    void validate() const;     // throws InputError
};

// Runs training, writing progress lines to `progress`.
void train(const TrainOptions& options, std::ostream& progress);

}  // namespace lh::net
