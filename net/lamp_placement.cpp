#include "net/lamp_placement.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace lh::net {

namespace {

// The median of `values` (by copy; the upper middle of an even count); NaN for none.
double median(std::vector<double> values) {
    if (values.empty()) return std::nan("");
    const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

}  // namespace

std::string lampPlacementCsv(const std::vector<LampPlacement>& lamps) {
    std::ostringstream csv;
    csv << "example,envmap,lamp,alpha,degrees_to_nearest_highlight\n";
    for (const LampPlacement& l : lamps)
        csv << l.example << ',' << l.envmap << ',' << l.lamp << ',' << l.alpha << ',' << l.degrees
            << '\n';
    return csv.str();
}

std::string lampPlacementMarkdown(const std::vector<LampPlacement>& lamps) {
    if (lamps.empty()) return "";
    std::vector<double> degrees, alphas;
    std::size_t placed = 0;
    for (const LampPlacement& l : lamps) {
        alphas.push_back(l.alpha);
        if (std::isnan(l.degrees)) continue;
        degrees.push_back(l.degrees);
        if (l.degrees <= kLampPlacedDegrees) ++placed;
    }
    std::ostringstream md;
    md << "\nLamps of the emitter head (lamps.csv), " << lamps.size()
       << " lamp-envmap pairs: median opacity " << std::setprecision(3) << median(alphas);
    if (degrees.empty()) {
        md << "; no ground-truth envmap has a highlight to place them against.\n";
        return md.str();
    }
    md << "; seen from the envmap's point, median " << std::fixed << std::setprecision(1)
       << median(degrees) << " deg from the nearest true lamp or window, " << std::setprecision(0)
       << 100.0 * double(placed) / double(degrees.size()) << "% within " << kLampPlacedDegrees
       << " deg";
    if (degrees.size() < lamps.size())
        md << " (" << lamps.size() - degrees.size() << " of the pairs left out: no true highlight)";
    md << ".\n";
    return md.str();
}

}  // namespace lh::net
