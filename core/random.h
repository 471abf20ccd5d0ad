// Small deterministic random numbers (scene generator, baker, object insertion): the same seed
// gives the same scene on every machine and thread count (std distributions are not
// specified bit-exactly across standard libraries, so we do not use them).
#pragma once

#include <cstdint>

namespace lh {

// SplitMix64: a full-period 64-bit generator, good enough for sampling and fast to seed.
class Random {
public:
    explicit Random(uint64_t seed) : state_(seed) {}
    uint64_t next() {
        uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return (next() >> 11) * (1.0 / 9007199254740992.0); }  // [0, 1)
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    int integer(int lo, int hi) { return lo + int(next() % uint64_t(hi - lo + 1)); }  // [lo, hi]
    bool chance(double p) { return uniform() < p; }

private:
    uint64_t state_;
};

// Independent streams from (seed, index) pairs.
inline uint64_t mixSeed(uint64_t seed, uint64_t index) {
    Random r(seed ^ (index * 0xD1B54A32D192ED03ull));
    return r.next();
}

}  // namespace lh
