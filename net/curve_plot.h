// The training curves as a PNG picture, drawn by the project's plot writer (image/plot.h).
// Each series gets its own panel with its own y range; all panels share the x range.
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
