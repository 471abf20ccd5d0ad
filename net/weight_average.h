// An exponential moving average of a network's weights, the model that training writes and
// validates. With batch 1 each Adam step moves the weights by one example's gradient, and the
// development rooms' score of consecutive checkpoints swung by 0.5 dB (15.03, 14.92, 14.56 dB
// at iterations 500, 900 and 1000 of one run); the average over the last ~1/(1 - decay) steps
// keeps what they agree on (Polyak averaging).
#pragma once

#include "net/lighthouse_net.h"

namespace lh::net {

// average <- decay * average + (1 - decay) * current, for every parameter; buffers are copied.
// Both networks of the same configuration; no autograd.
void updateWeightAverage(LighthouseNet& average, LighthouseNet& current, double decay);

}  // namespace lh::net
