// Luminance of linear RGB with the Rec. 709 (sRGB) primaries, shared by the metrics, the data
// generator's exposure statistics and the training losses so that all three weigh colour alike.
#pragma once

namespace lh {

// Y = kLumaR R + kLumaG G + kLumaB B (relative luminance; white (1, 1, 1) has Y = 1).
constexpr double kLumaR = 0.2126, kLumaG = 0.7152, kLumaB = 0.0722;

// Luminance above which a pixel is a lamp or a window: where an exposed photo clips, and what
// a display shows white.
constexpr double kLampLuminance = 1.0;

// Y of one linear RGB pixel (three floats); negative components are weighed as they are.
inline double rec709Luminance(const float* rgb) {
    return kLumaR * rgb[0] + kLumaG * rgb[1] + kLumaB * rgb[2];
}

// Whether a linear RGB pixel is a lamp or a window: its luminance is above kLampLuminance.
inline bool isLampOrWindow(const float* rgb) { return rec709Luminance(rgb) > kLampLuminance; }

}  // namespace lh
