#include "net/weight_average.h"

namespace lh::net {

void updateWeightAverage(LighthouseNet& average, LighthouseNet& current, double decay) {
    torch::NoGradGuard noGrad;
    const auto parameters = current->named_parameters();
    for (auto& p : average->named_parameters())
        p.value().mul_(decay).add_(parameters[p.key()], 1.0 - decay);
    const auto buffers = current->named_buffers();
    for (auto& b : average->named_buffers()) b.value().copy_(buffers[b.key()]);
}

}  // namespace lh::net
