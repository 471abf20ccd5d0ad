#include "net/eval_pairs.h"

#include "core/errors.h"
#include "image/metrics.h"

#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <utility>

namespace lh::net {

namespace {

using EnvmapKey = std::pair<std::string, std::size_t>;  // (example, envmap)

// Which way each metrics.csv column improves (image/metrics.h kEnvmapMetricColumnNames).
int betterDirection(const std::string& column) {
    if (column == "radiance_ratio" || column == "srgb_bias_unobserved") return 0;
    if (column.rfind("psnr", 0) == 0 || column.rfind("highlight", 0) == 0) return 1;
    return -1;
}

std::map<EnvmapKey, const MetricValues*> rowsOf(const std::vector<EvalCsvRow>& rows,
                                                const std::string& method,
                                                const std::string& which) {
    std::map<EnvmapKey, const MetricValues*> out;
    for (const EvalCsvRow& r : rows)
        if (r.method == method && !out.emplace(EnvmapKey{r.example, r.envmap}, &r.values).second)
            throw InputError(which + " scores envmap " + std::to_string(r.envmap) +
                             " of example '" + r.example + "' twice for method '" + method + "'");
    return out;
}

std::string methodsOf(const std::vector<EvalCsvRow>& rows) {
    std::set<std::string> names;
    for (const EvalCsvRow& r : rows) names.insert(r.method);
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
    return out.empty() ? "none" : out;
}

}  // namespace

std::vector<PairedDifference> pairedDifferences(const std::vector<EvalCsvRow>& a,
                                                const std::vector<EvalCsvRow>& b,
                                                const std::string& method) {
    const auto inA = rowsOf(a, method, "the first evaluation");
    const auto inB = rowsOf(b, method, "the second evaluation");
    std::vector<std::pair<const MetricValues*, const MetricValues*>> pairs;
    for (const auto& [key, values] : inA) {
        const auto it = inB.find(key);
        if (it != inB.end()) pairs.push_back({values, it->second});
    }
    if (pairs.empty())
        throw InputError("no envmap of method '" + method +
                         "' is scored by both evaluations (methods of the first: " + methodsOf(a) +
                         "; of the second: " + methodsOf(b) + ")");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<PairedDifference> out;
    for (std::size_t c = 0; c < kEnvmapMetricColumns; ++c) {
        PairedDifference d;
        d.metric = kEnvmapMetricColumnNames[c];
        d.better = betterDirection(d.metric);
        std::vector<double> differences;
        for (const auto& [x, y] : pairs)
            if (std::isfinite((*x)[c]) && std::isfinite((*y)[c]))
                differences.push_back((*y)[c] - (*x)[c]);
        // meanStd's population deviation over sqrt(n - 1): the sample deviation over sqrt(n).
        const MeanStd m = meanStd(differences);
        d.pairs = m.count;
        d.mean = m.mean;  // NaN without pairs
        d.standardError = m.count < 2 ? nan : m.std / std::sqrt(double(m.count - 1));
        out.push_back(d);
    }
    return out;
}

std::string pairedDifferencesMarkdown(const std::vector<PairedDifference>& diffs,
                                      const std::string& nameA, const std::string& nameB,
                                      const std::string& method) {
    std::ostringstream out;
    out << "Paired difference B - A of method '" << method
        << "', per envmap both score (A: " << nameA << "; B: " << nameB
        << "); standard error of the mean difference:\n\n"
        << "| metric | pairs | B - A | standard error | reading |\n|---|---|---|---|---|\n";
    for (const PairedDifference& d : diffs) {
        std::string reading = "within 2 standard errors of 0";
        if (!std::isfinite(d.mean) || !std::isfinite(d.standardError))
            reading = "too few pairs";
        else if (d.mean == 0 && d.standardError == 0)
            reading = "the same on every envmap";
        else if (std::abs(d.mean) >= 2 * d.standardError)
            reading = d.better == 0                    ? (d.mean > 0 ? "higher" : "lower")
                      : (d.mean > 0) == (d.better > 0) ? "B better"
                                                       : "B worse";
        out << "| " << d.metric << " | " << d.pairs << " | " << std::showpos << std::fixed
            << std::setprecision(4) << d.mean << std::noshowpos << " | " << d.standardError << " | "
            << reading << " |\n";
    }
    return out.str();
}

}  // namespace lh::net
