// ln x for x in [1, 2], inlined: the ray marcher takes one per ray that crosses T = 1/2 (where
// it "hits" the scene), and a libm call there cost ~3% of an envmap's instructions.
//
// ln x = 2 atanh(s) with s = (x - 1) / (x + 1) in [0, 1/3]: 2 (s + s^3/3 + ... + s^17/17).
// The first term left out, 2 s^19 / 19, is below 1e-10 (s <= 1/3); relative to ln x it is
// below 2 s^18 / 19 <= 2.4e-10. Measured against std::log in tests/core/fast_log_test.cpp.
// Outside [1, 2] (and for NaN) it defers to std::log.
#pragma once

#include <cmath>

namespace lh {

inline double logOfOneToTwo(double x) {
    if (!(x >= 1.0 && x <= 2.0)) return std::log(x);
    const double s = (x - 1.0) / (x + 1.0), s2 = s * s;
    // s (1 + s2/3 + s2^2/5 + ... + s2^8/17), Estrin's scheme for a short latency.
    const double s4 = s2 * s2, s8 = s4 * s4;
    // Coefficients as constant products: a division by 3.0 would stay a division.
    const double p01 = 1.0 + s2 * (1.0 / 3), p23 = 1.0 / 5 + s2 * (1.0 / 7),
                 p45 = 1.0 / 9 + s2 * (1.0 / 11), p67 = 1.0 / 13 + s2 * (1.0 / 15);
    const double q0 = p01 + p23 * s4, q1 = p45 + p67 * s4;
    const double series = q0 + q1 * s8 + s8 * s8 * (1.0 / 17);
    return 2.0 * s * series;
}

}  // namespace lh
