// Paired differences between two evaluations of the same envmaps (`lighthouse eval-diff`): for
// each metric of metrics.csv, the mean over the envmaps both score of (B - A) and its standard
// error. Two models scored on the same test set differ per envmap far less than the envmaps
// differ from each other, so the paired difference resolves changes (a tenth of a dB) that
// the two tables' means +- std hide.
#pragma once

#include "net/eval_table.h"

#include <string>
#include <vector>

namespace lh::net {

struct PairedDifference {
    std::string metric;        // the metrics.csv column
    int pairs = 0;             // envmaps where both values are finite
    double mean = 0;           // mean of B - A; NaN without pairs
    double standardError = 0;  // sample std of B - A over sqrt(pairs); NaN below two pairs
    // +1 where larger is better (PSNR, highlight recall), -1 where smaller is (angles,
    // errors), 0 where neither (the radiance ratio and display bias, best at 1 and 0).
    int better = 0;
};

// The rows of `method` in `a` and `b`, paired by (example, envmap), one difference per metric
// column in metrics.csv's order. Throws InputError when an envmap appears twice for `method`
// in one of them, or when no envmap of `method` is in both (naming the methods each has).
std::vector<PairedDifference> pairedDifferences(const std::vector<EvalCsvRow>& a,
                                                const std::vector<EvalCsvRow>& b,
                                                const std::string& method);

// A Markdown table of `diffs`: metric, pairs, mean of B - A, standard error, and whether the
// difference is at least two standard errors from 0 in the better or worse direction (or 0 on
// every envmap).
std::string pairedDifferencesMarkdown(const std::vector<PairedDifference>& diffs,
                                      const std::string& nameA, const std::string& nameB,
                                      const std::string& method);

}  // namespace lh::net
