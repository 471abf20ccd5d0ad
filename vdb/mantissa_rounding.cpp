#include "vdb/mantissa_rounding.h"

#include "core/errors.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

namespace lh {

namespace {

void requireBits(int bits) {
    if (bits < kMinMantissaBits || bits > kMaxMantissaBits)
        throw InputError("mantissa bits must be in [" + std::to_string(kMinMantissaBits) + ", " +
                         std::to_string(kMaxMantissaBits) + "], got " + std::to_string(bits));
}

// Assumes requireBits has passed.
float roundChecked(float x, int bits) {
    if (!std::isfinite(x)) return x;
    std::uint32_t u;
    std::memcpy(&u, &x, sizeof u);
    const int dropped = 23 - bits;
    const std::uint32_t keep = ~((std::uint32_t(1) << dropped) - 1);
    // Adding half of the dropped range to the magnitude bits rounds to nearest; a carry out of
    // the mantissa moves to the next exponent, which is the right rounding too (IEEE-754
    // magnitudes are ordered as integers). The sign bit is never reached: the largest finite
    // magnitude plus the increment stays below 2^31.
    const std::uint32_t rounded = (u + (std::uint32_t(1) << (dropped - 1))) & keep;
    float y;
    std::memcpy(&y, &rounded, sizeof y);
    if (std::isfinite(y)) return y;
    const std::uint32_t truncated = u & keep;  // rounding up overflowed to Inf
    std::memcpy(&y, &truncated, sizeof y);
    return y;
}

openvdb::Vec3s roundChecked(const openvdb::Vec3s& v, int bits) {
    return openvdb::Vec3s(roundChecked(v.x(), bits), roundChecked(v.y(), bits),
                          roundChecked(v.z(), bits));
}

template <typename GridT>
void roundGrid(GridT& grid, int bits) {
    requireBits(bits);
    for (auto it = grid.beginValueAll(); it; ++it) it.setValue(roundChecked(*it, bits));
    grid.tree().root().setBackground(roundChecked(grid.background(), bits), true);
}

}  // namespace

float roundToMantissaBits(float x, int bits) {
    requireBits(bits);
    return roundChecked(x, bits);
}

void roundGridToMantissaBits(openvdb::FloatGrid& grid, int bits) { roundGrid(grid, bits); }
void roundGridToMantissaBits(openvdb::Vec3SGrid& grid, int bits) { roundGrid(grid, bits); }

void validateMantissaBits(int bits, bool halfPrecision, const char* option) {
    if (bits == 0) return;
    const int most = halfPrecision ? kHalfMantissaBits - 1 : kMaxMantissaBits;
    if (bits < kMinMantissaBits || bits > most)
        throw InputError(std::string(option) + " must be in [" + std::to_string(kMinMantissaBits) +
                         ", " + std::to_string(most) + "]" +
                         (halfPrecision ? " for half precision (half floats keep 10 bits)" : "") +
                         ", got " + std::to_string(bits));
}

}  // namespace lh
