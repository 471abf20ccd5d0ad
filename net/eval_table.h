// The pieces of `lighthouse eval`'s output that need no network: the CSV rows, the Markdown
// table (Table 2) and the contact sheet, and the merge of a set of eval shards (core/shard.h)
// into the files one run writes: metrics.csv, table.md and contact_sheet.png, the same bytes.
#pragma once

#include "image/metrics.h"
#include "net/evaluation.h"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace lh {
struct ImageRGB;
}

namespace lh::net {

// Columns of metrics.csv after example, envmap and method: image/metrics.h metricColumns.
using MetricValues = std::array<double, kEnvmapMetricColumns>;

// Contact sheet: rows of ground truth | predictions, 90 pixels high, the first 12 envmaps.
constexpr int kEvalSheetTileHeight = 90;
constexpr std::size_t kEvalSheetRows = 12;

std::string evalCsvHeader();
// One row; `exact` writes 17 significant digits (a shard's CSV, read back by the merge),
// otherwise the stream's default 6 (metrics.csv).
std::string evalCsvRow(const std::string& example, std::size_t envmap, const std::string& method,
                       const MetricValues& values, bool exact);
void addScores(MethodScores& scores, const MetricValues& values);

// One row of metrics.csv (or of an eval shard's CSV), as evalCsvRow writes it.
struct EvalCsvRow {
    std::string example;
    std::size_t envmap = 0;
    std::string method;
    MetricValues values{};
};
// The rows of the metrics.csv (or shard CSV) at `path`, in file order. Throws FileError if it
// cannot be read, its header is not evalCsvHeader(), or a row is malformed.
std::vector<EvalCsvRow> readEvalCsv(const std::string& path);

// Table 2 in Markdown, with its note on `envmaps` of `scenes` scenes of `data`.
std::string evalTableMarkdown(const std::vector<MethodScores>& methods, std::size_t scenes,
                              const std::string& data, const std::string& configName);

// The notes under Table 2 on how "ours" was predicted, when not as predict does by default:
// --highlight-gain (a gain other than 1, with its --highlight-knee), --shell and
// --unclipped-photos. Empty when none.
std::string evalPredictionNotes(double highlightGain, double highlightKnee, bool shell,
                                bool unclippedPhotos = false);

// The headroom section (EvalOptions::headroom): `ours` and each of `rows` (ours with one part
// of the truth put in) on PSNR, angle, irradiance error and radiance ratio over all pixels.
std::string headroomTableMarkdown(const MethodScores& ours, const std::vector<MethodScores>& rows);

// A one-row contact sheet, the strip of rows that `stackSheetStrips` stacks into the sheet
// contactSheet() would have made of all rows at once.
ImageRGB sheetStrip(const std::vector<ImageRGB>& row);
ImageRGB stackSheetStrips(const std::vector<ImageRGB>& strips);

// Merges the eval shards in `dir` (each wrote shard-K-of-N.json, metrics.shard-K-of-N.csv and
// sheet.shard-K-of-N/): writes table.md, metrics.csv and contact_sheet.png and returns the
// table. Throws FileError if a shard is missing, the records disagree, or `dir` was merged
// already (it holds table.md).
std::string mergeEvalShards(const std::string& dir);

}  // namespace lh::net
