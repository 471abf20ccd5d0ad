// A linear RGB float image: the one in-memory picture type of the project.
#pragma once

#include <cstddef>
#include <vector>

namespace lh {

struct ImageRGB {
    int width = 0;
    int height = 0;
    std::vector<float> pixels;  // row-major, 3 floats per pixel, linear radiance

    ImageRGB() = default;
    ImageRGB(int w, int h) : width(w), height(h), pixels(std::size_t(w) * h * 3, 0.f) {}

    float* at(int x, int y) { return &pixels[(std::size_t(y) * width + x) * 3]; }
    const float* at(int x, int y) const { return &pixels[(std::size_t(y) * width + x) * 3]; }
    bool empty() const { return width == 0 || height == 0; }
};

}  // namespace lh
