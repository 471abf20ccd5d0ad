// Line plots as PNG pictures (training curves), drawn with stb_easy_font labels so that no
// plotting package is needed. Each series gets its own panel with its own y range.
#pragma once

#include <string>
#include <vector>

namespace lh::net {

struct CurveSeries {
    std::string name;
    std::vector<double> x, y;
};

// Writes a PNG (atomically) of `series` stacked in panels against a shared x axis.
void writeCurvePlot(const std::string& path, const std::string& title, const std::string& xLabel,
                    const std::vector<CurveSeries>& series);

}  // namespace lh::net
