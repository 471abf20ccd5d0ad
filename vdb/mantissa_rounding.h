// Lossy storage by precision: floats rounded to fewer mantissa bits before a file is written.
// A 32-bit float keeps 23 explicit mantissa bits; rounding to N of them leaves the low 23 - N
// bits zero, and Blosc's byte shuffle (which OpenVDB applies to every Blosc-compressed grid)
// then stores those zero bytes almost for free. The values read back are ordinary floats that
// any OpenVDB reader takes; each is within a relative 2^-(N+1) of the original (7 bits, the
// precision of bfloat16: 0.4%).
#pragma once

#include <openvdb/openvdb.h>

namespace lh {

// Explicit mantissa bits a rounding may keep: 1 (relative error 25%) to 22 (1.2e-7).
constexpr int kMinMantissaBits = 1, kMaxMantissaBits = 22;
// Half floats keep 10 explicit bits, so rounding before a half-precision write needs fewer.
constexpr int kHalfMantissaBits = 10;

// `x` rounded to `bits` explicit mantissa bits, to nearest (ties away from zero). Zero,
// subnormal-free magnitudes, and signs are kept; a value that would round past the largest
// finite float is truncated instead, so the result is always finite for finite `x`.
// Non-finite `x` comes back unchanged. Throws InputError for bits outside
// [kMinMantissaBits, kMaxMantissaBits].
float roundToMantissaBits(float x, int bits);

// Rounds every value of the grid (active and inactive voxels, tiles, background) in place.
void roundGridToMantissaBits(openvdb::FloatGrid& grid, int bits);
void roundGridToMantissaBits(openvdb::Vec3SGrid& grid, int bits);

// Throws InputError naming `option` unless `bits` is 0 (no rounding) or within the range
// above, and within half precision's 10 bits when `halfPrecision` (more would do nothing).
void validateMantissaBits(int bits, bool halfPrecision, const char* option = "--mantissa-bits");

}  // namespace lh
