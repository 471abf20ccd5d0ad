// `lighthouse compare PRED.exr GT.exr [--mask M.png]`
// `lighthouse compare --batch PRED_DIR GT_DIR [--csv out.csv]`
// The metrics of docs/conventions.md#metrics and the two HDR ones of docs/metrics.md,
// implemented in image/metrics.h.
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/dataset_files.h"
#include "core/errors.h"
#include "core/path_guard.h"
#include "image/highlights.h"
#include "image/image_io.h"
#include "image/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <regex>
#include <string>
#include <vector>

namespace lh::cli {

namespace {

namespace fs = std::filesystem;

struct CompareOptions {
    std::string pred;  // a file, or a directory with --batch
    std::string gt;
    std::string mask;
    bool batch = false;
    std::string csv;
    // How far a predicted highlight may lie from a true one and still match, in degrees.
    double highlightRadius = kHighlightRadiusDegrees;
};

// One ground-truth envmap of a batch and the files that go with it.
struct EnvmapPair {
    std::string relative;  // path under GT_DIR, '/'-separated
    std::string pred, gt;
    std::string mask;  // "" when the ground truth has no env_<k>_mask.png beside it
};

// Loads and compares one pair, highlights matched within `highlightRadius` degrees; metric
// errors (sizes, NaN) are prefixed with both file names.
EnvmapMetrics compareFiles(const std::string& predPath, const std::string& gtPath,
                           const std::string& maskPath, double highlightRadius) {
    const ImageRGB pred = readImage(predPath);
    const ImageRGB gt = readImage(gtPath);
    std::vector<std::uint8_t> mask;
    if (!maskPath.empty()) mask = loadMask(maskPath, gt.width, gt.height);
    try {
        return compareEnvmaps(pred, gt, maskPath.empty() ? nullptr : &mask, highlightRadius);
    } catch (const InputError& e) {
        throw InputError("'" + predPath + "' vs '" + gtPath + "': " + e.what());
    }
}

std::string formatNumber(const char* format, double value) {
    char text[64];
    std::snprintf(text, sizeof text, format, value);
    return text;
}

// Two decimals; "inf" for identical images, "n/a" for a metric with no pixel to average.
std::string formatMetric(double value) {
    if (std::isnan(value)) return "n/a";
    if (std::isinf(value)) return "inf";
    return formatNumber("%.2f", value);
}

// "mean ± std", with "(k of N)" when only k of the N envmaps have a value (NaN entries left
// out), as eval's table writes it.
std::string formatMeanStd(const MeanStd& s, int total) {
    std::string text = formatMetric(s.mean);
    if (std::isfinite(s.mean)) text += " ± " + formatMetric(s.std);
    if (s.count != total)
        text += " (" + std::to_string(s.count) + " of " + std::to_string(total) + ")";
    return text;
}

// Left-aligned in `width` columns; counts UTF-8 code points, since "±" is two bytes.
std::string padded(const std::string& text, std::size_t width) {
    std::size_t columns = 0;
    for (unsigned char c : text) columns += (c & 0xC0) != 0x80;
    return text + std::string(columns < width ? width - columns : 1, ' ');
}

// One row of the table: label, then PSNR, RGB angle, log-luminance RMSE, irradiance error,
// mean radiance ratio. The last two are over the whole sphere, so the observed row has "-".
void printRow(const std::string& label, const std::string& psnr, const std::string& angle,
              const std::string& logLuminance, const std::string& irradiance,
              const std::string& radianceRatio) {
    std::cout << padded(label, 20) << padded(psnr, 22) << padded(angle, 26)
              << padded(logLuminance, 24) << padded(irradiance, 24) << radianceRatio << "\n";
}

void printHeader() {
    printRow("", "PSNR (dB)", "RGB angular error (deg)", "log-luminance RMSE",
             "irradiance rel. error", "radiance ratio");
}

// The display bias over the unobserved pixels, one line below the table, and their PSNR with
// it taken out (psnrWithoutBias): how much of the invented part's error is its brightness.
void printDisplayBias(double bias, double psnrWithout) {
    std::cout << "display bias over unobserved content: " << formatNumber("%+.4f", bias)
              << " (mean sRGB difference; positive: brighter than the truth); without it, PSNR "
              << formatNumber("%.2f", psnrWithout) << " dB\n";
}

// The lamps and windows (image/highlights.h), one line below the table: recall and precision,
// "none" where no envmap has a highlight on the side the share is taken of (the truth for the
// recall, the prediction for the precision).
void printHighlights(double radius, const std::string& recall, const std::string& precision) {
    std::cout << "lamps and windows (luminance > 1) within " << radius << " deg: recall " << recall
              << ", precision " << precision << "\n";
}

std::string highlightText(double share) {
    return std::isnan(share) ? std::string("none") : formatMetric(share);
}

std::string highlightText(const std::vector<double>& shares, int total) {
    const MeanStd s = meanStd(shares);
    return s.count == 0 ? std::string("none") : formatMeanStd(s, total);
}

void compareSingle(const CompareOptions& o) {
    const EnvmapMetrics m = compareFiles(o.pred, o.gt, o.mask, o.highlightRadius);
    printHeader();
    printRow("all content", formatMetric(m.psnrAll), formatMetric(m.angularAll),
             formatMetric(m.logLuminanceAll), formatMetric(m.irradianceError),
             formatMetric(m.radianceRatio));
    printHighlights(o.highlightRadius, highlightText(m.highlightRecall),
                    highlightText(m.highlightPrecision));
    if (o.mask.empty()) return;
    if (std::isnan(m.psnrObserved))
        std::cout << padded("observed content", 20) << "no observed pixels in '" << o.mask << "'\n";
    else
        printRow("observed content", formatMetric(m.psnrObserved), formatMetric(m.angularObserved),
                 formatMetric(m.logLuminanceObserved), "-", "-");
    if (!std::isnan(m.psnrUnobserved)) {
        printRow("unobserved content", formatMetric(m.psnrUnobserved), "-", "-", "-", "-");
        printDisplayBias(m.displayBiasUnobserved,
                         psnrWithoutBias(m.psnrUnobserved, m.displayBiasUnobserved));
    }
}

void requireDirectory(const std::string& path, const std::string& what) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw FileError(what + " '" + path + "' does not exist");
    if (!fs::is_directory(path, ec)) throw FileError(what + " '" + path + "' is not a directory");
}

// Every env_<k>.exr under GT_DIR (so not env_<k>_pos.exr nor masks), in path order, with its
// prediction at the same relative path under PRED_DIR. A missing prediction is an error:
// leaving it out would flatter the means.
std::vector<EnvmapPair> findPairs(const std::string& predDir, const std::string& gtDir) {
    requireDirectory(gtDir, "ground-truth directory");
    requireDirectory(predDir, "prediction directory");
    static const std::regex envmapName(dataset::kEnvmapExrPattern);
    std::vector<EnvmapPair> pairs;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(gtDir, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code typeError;
        const fs::path& gt = it->path();
        if (!it->is_regular_file(typeError) ||
            !std::regex_match(gt.filename().string(), envmapName))
            continue;
        const fs::path relative = gt.lexically_relative(gtDir);
        const fs::path mask = gt.parent_path() / dataset::maskPng(gt.stem().string());
        pairs.push_back({relative.generic_string(), (fs::path(predDir) / relative).string(),
                         gt.string(), fs::exists(mask, typeError) ? mask.string() : ""});
    }
    if (ec) throw FileError("cannot walk '" + gtDir + "': " + ec.message());
    if (pairs.empty()) throw InputError("no envmaps env_<k>.exr under '" + gtDir + "'");
    std::sort(pairs.begin(), pairs.end(),
              [](const EnvmapPair& a, const EnvmapPair& b) { return a.relative < b.relative; });
    for (const EnvmapPair& p : pairs) {
        std::error_code missing;
        if (!fs::is_regular_file(p.pred, missing))
            throw FileError("no prediction '" + p.pred + "' for ground truth '" + p.gt + "'");
    }
    return pairs;
}

// CSV field: quoted when it holds a separator, a quote or a line break.
std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

// One row per envmap; "nan" where a metric has no pixel (no mask, or a black ground truth
// for the irradiance error), "inf" for identical maps, both of which Python's float() and
// pandas read. New columns go at the end, so scripts that index the first five keep working.
void writeCsv(AtomicOutput& out, const std::vector<EnvmapPair>& pairs,
              const std::vector<EnvmapMetrics>& metrics) {
    {
        std::ofstream file(out.tempPath());
        file << "envmap," << metricColumnsCsvHeader() << "\n";
        for (std::size_t i = 0; i < pairs.size(); ++i) {
            const EnvmapMetrics& m = metrics[i];
            file << csvField(pairs[i].relative);
            for (double v : metricColumns(m)) file << "," << formatNumber("%.8g", v);
            file << "\n";
        }
        file.close();
        if (!file) throw FileError("cannot write '" + out.finalPath() + "'");
    }
    out.commit();
}

void compareBatch(const CompareOptions& o) {
    // Created first so that a bad --csv path fails before the work, not after it.
    std::unique_ptr<AtomicOutput> csv;
    if (!o.csv.empty()) csv = std::make_unique<AtomicOutput>(o.csv);

    const std::vector<EnvmapPair> pairs = findPairs(o.pred, o.gt);
    if (!o.csv.empty()) {
        std::vector<NamedInput> inputs;
        for (const EnvmapPair& p : pairs)
            inputs.insert(inputs.end(), {{p.pred, "a prediction in PRED_DIR"},
                                         {p.gt, "a ground truth in GT_DIR"},
                                         {p.mask, "a mask in GT_DIR"}});
        requireOutputIsNotAnInput(o.csv, "--csv", inputs);
    }
    const int total = int(pairs.size());
    const int progressStep = std::max(1, total / 10);
    std::vector<EnvmapMetrics> metrics;
    std::vector<double> psnrAll, angularAll, psnrObserved, angularObserved;
    std::vector<double> logLuminanceAll, logLuminanceObserved, irradiance, radianceRatio;
    std::vector<double> psnrUnobserved, biasUnobserved, unobservedWithoutBias;
    std::vector<double> highlightRecall, highlightPrecision;
    int withMask = 0;
    for (const EnvmapPair& p : pairs) {
        const EnvmapMetrics m = compareFiles(p.pred, p.gt, p.mask, o.highlightRadius);
        metrics.push_back(m);
        psnrAll.push_back(m.psnrAll);
        angularAll.push_back(m.angularAll);
        logLuminanceAll.push_back(m.logLuminanceAll);
        irradiance.push_back(m.irradianceError);
        radianceRatio.push_back(m.radianceRatio);
        highlightRecall.push_back(m.highlightRecall);
        highlightPrecision.push_back(m.highlightPrecision);
        if (!p.mask.empty()) {
            ++withMask;
            psnrObserved.push_back(m.psnrObserved);
            angularObserved.push_back(m.angularObserved);
            logLuminanceObserved.push_back(m.logLuminanceObserved);
            psnrUnobserved.push_back(m.psnrUnobserved);
            biasUnobserved.push_back(m.displayBiasUnobserved);
            unobservedWithoutBias.push_back(
                psnrWithoutBias(m.psnrUnobserved, m.displayBiasUnobserved));
        }
        const int done = int(metrics.size());
        if (total > 20 && (done % progressStep == 0 || done == total))
            std::cerr << "compared " << done << "/" << total << " envmaps\n";
    }
    if (csv) writeCsv(*csv, pairs, metrics);

    std::cout << total << " envmaps, " << withMask << " with an observed mask (mean ± std)\n";
    printHeader();
    printRow(
        "all content", formatMeanStd(meanStd(psnrAll), total),
        formatMeanStd(meanStd(angularAll), total), formatMeanStd(meanStd(logLuminanceAll), total),
        formatMeanStd(meanStd(irradiance), total), formatMeanStd(meanStd(radianceRatio), total));
    if (withMask > 0)
        printRow("observed content", formatMeanStd(meanStd(psnrObserved), withMask),
                 formatMeanStd(meanStd(angularObserved), withMask),
                 formatMeanStd(meanStd(logLuminanceObserved), withMask), "-", "-");
    if (withMask > 0 && meanStd(psnrUnobserved).count > 0) {
        printRow("unobserved content", formatMeanStd(meanStd(psnrUnobserved), withMask), "-", "-",
                 "-", "-");
        printDisplayBias(meanStd(biasUnobserved).mean, meanStd(unobservedWithoutBias).mean);
    }
    printHighlights(o.highlightRadius, highlightText(highlightRecall, total),
                    highlightText(highlightPrecision, total));
    if (csv) std::cout << "per-envmap rows: " << csv->finalPath() << "\n";
}

}  // namespace

void addCompareCommand(CLI::App& app) {
    auto o = std::make_shared<CompareOptions>();
    CLI::App* cmd = app.add_subcommand(
        "compare",
        "PSNR, RGB angular error, log-luminance RMSE, irradiance error, mean radiance ratio "
        "and where the lamps and windows are (highlight recall and precision) of predicted "
        "envmaps against ground truth, and with a mask the PSNR and display bias of the "
        "unobserved pixels (docs/metrics.md)");
    cmd->add_option("pred", o->pred, "Predicted envmap (.exr), or PRED_DIR with --batch")
        ->required();
    cmd->add_option("gt", o->gt, "Ground-truth envmap (.exr), or GT_DIR with --batch")->required();
    CLI::Option* batch =
        cmd->add_flag("--batch", o->batch,
                      "Compare every env_<k>.exr under GT_DIR with the same path under PRED_DIR; "
                      "env_<k>_mask.png beside a ground truth is its observed mask");
    cmd->add_option("--mask", o->mask, "Observed-pixel mask (.png, nonzero = observed)")
        ->excludes(batch);
    cmd->add_option("--csv", o->csv, "With --batch, write one row of metrics per envmap")
        ->needs(batch);
    cmd->add_option("--highlight-radius", o->highlightRadius,
                    "Degrees within which a predicted lamp or window matches a true one, for the "
                    "highlight recall and precision (a wider radius forgives a lamp drawn too "
                    "wide or a little off)")
        ->check(CLI::Range(0.1, 180.0))
        ->capture_default_str();
    cmd->callback([o] { o->batch ? compareBatch(*o) : compareSingle(*o); });
}

}  // namespace lh::cli
