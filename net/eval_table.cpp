#include "net/eval_table.h"

#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/shard.h"
#include "image/contact_sheet.h"
#include "image/highlights.h"
#include "image/image.h"
#include "image/image_io.h"
#include "image/metrics.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

namespace fs = std::filesystem;

namespace lh::net {

namespace {

constexpr int kSheetGap = 4;  // contactSheet's default

std::string cell(const std::vector<double>& values, int precision) {
    const MeanStd m = meanStd(values);
    std::ostringstream out;
    out << std::fixed << std::setprecision(precision) << m.mean << " +- " << m.std;
    return out.str();
}

// As cell, and how many values it holds of all: for metrics that an envmap may not have.
std::string countedCell(const std::vector<double>& values, int precision) {
    return cell(values, precision) + " (" + std::to_string(meanStd(values).count) + " of " +
           std::to_string(values.size()) + ")";
}

// As cell, with the mean's sign always shown.
std::string signedCell(const std::vector<double>& values, int precision) {
    const MeanStd m = meanStd(values);
    std::ostringstream out;
    out << std::fixed << std::showpos << std::setprecision(precision) << m.mean << std::noshowpos
        << " +- " << m.std;
    return out.str();
}

// psnrWithoutBias of each envmap.
std::vector<double> withoutBias(const std::vector<double>& psnrDb,
                                const std::vector<double>& bias) {
    std::vector<double> out(psnrDb.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = psnrWithoutBias(psnrDb[i], bias[i]);
    return out;
}

// Parses a row written by evalCsvRow; throws FileError naming `where`.
EvalCsvRow parseCsvRow(const std::string& line, const std::string& where) {
    EvalCsvRow row;
    const auto bad = [&] { return FileError("'" + where + "': malformed row '" + line + "'"); };
    const std::size_t c1 = line.find(','),
                      c2 = c1 == std::string::npos ? c1 : line.find(',', c1 + 1);
    if (c2 == std::string::npos || line.size() < c2 + 2 || line[c2 + 1] != '"') throw bad();
    const std::size_t q = line.find('"', c2 + 2);
    if (q == std::string::npos) throw bad();
    row.example = line.substr(0, c1);
    row.envmap = std::size_t(std::strtoul(line.substr(c1 + 1, c2 - c1 - 1).c_str(), nullptr, 10));
    row.method = line.substr(c2 + 2, q - c2 - 2);
    const char* p = line.c_str() + q + 1;
    for (double& v : row.values) {
        if (*p != ',') throw bad();
        char* end = nullptr;
        v = std::strtod(p + 1, &end);
        if (end == p + 1) throw bad();
        p = end;
    }
    if (*p != '\0') throw bad();
    return row;
}

}  // namespace

std::string evalCsvHeader() { return "example,envmap,method," + metricColumnsCsvHeader() + "\n"; }

std::vector<EvalCsvRow> readEvalCsv(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw FileError("cannot read eval metrics '" + path + "'");
    std::string line;
    std::getline(in, line);
    if (line + "\n" != evalCsvHeader())
        throw FileError("'" + path + "' is not an eval's metrics.csv (its header differs)");
    std::vector<EvalCsvRow> rows;
    while (std::getline(in, line))
        if (!line.empty()) rows.push_back(parseCsvRow(line, path));
    return rows;
}

std::string evalCsvRow(const std::string& example, std::size_t envmap, const std::string& method,
                       const MetricValues& values, bool exact) {
    std::ostringstream out;
    if (exact) out << std::setprecision(17);
    out << example << ',' << envmap << ",\"" << method << '"';
    for (double v : values) out << ',' << v;
    out << '\n';
    return out.str();
}

void addScores(MethodScores& s, const MetricValues& v) {
    s.psnrAll.push_back(v[0]);
    s.angularAll.push_back(v[1]);
    s.psnrObserved.push_back(v[2]);
    s.angularObserved.push_back(v[3]);
    s.logLuminanceAll.push_back(v[4]);
    s.logLuminanceObserved.push_back(v[5]);
    s.irradianceError.push_back(v[6]);
    s.radianceRatio.push_back(v[7]);
    s.psnrUnobserved.push_back(v[8]);
    s.displayBiasUnobserved.push_back(v[9]);
    s.highlightRecall.push_back(v[10]);
    s.highlightPrecision.push_back(v[11]);
}

std::string evalTableMarkdown(const std::vector<MethodScores>& methods, std::size_t scenes,
                              const std::string& data, const std::string& configName) {
    std::ostringstream md;
    md << "| method | PSNR all (dB) | angular all (deg) | PSNR observed (dB) | angular observed "
          "(deg) "
          "| log-lum RMSE all | log-lum RMSE observed | irradiance rel. error | radiance ratio |\n"
       << "|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& m : methods)
        md << "| " << m.name << " | " << cell(m.psnrAll, 2) << " | " << cell(m.angularAll, 2)
           << " | " << cell(m.psnrObserved, 2) << " | " << cell(m.angularObserved, 2) << " | "
           << cell(m.logLuminanceAll, 3) << " | " << cell(m.logLuminanceObserved, 3) << " | "
           << cell(m.irradianceError, 3) << " | " << cell(m.radianceRatio, 2) << " |\n";
    md << "\n"
       << (methods.empty() ? 0 : methods[0].psnrAll.size()) << " envmaps (" << scenes
       << " scenes) of `" << data << "`, model config `" << configName << "`; mean +- std. "
       << "Log-lum RMSE: of ln(1 + luminance); irradiance rel. error: |E_pred - E_gt| / E_gt at "
       << "the six axis normals; radiance ratio: mean luminance over the sphere, predicted / "
       << "true (1 = the right total light; docs/metrics.md).\n\n"
       << "What each method invents (the unobserved pixels); display bias: mean sRGB difference, "
       << "positive where the prediction is brighter than the truth; without the bias: the PSNR "
       << "if each envmap's invented part were shifted to the right mean brightness:\n\n"
       << "| method | PSNR unobserved (dB) | display bias unobserved | PSNR unobserved without "
          "the bias (dB) |\n|---|---|---|---|\n";
    for (const auto& m : methods)
        md << "| " << m.name << " | " << cell(m.psnrUnobserved, 2) << " | "
           << signedCell(m.displayBiasUnobserved, 3) << " | "
           << cell(withoutBias(m.psnrUnobserved, m.displayBiasUnobserved), 2) << " |\n";
    md << "\nLamps and windows, as a mirror ball would show them (pixels of luminance above 1): "
       << "recall, the share of the true ones (by solid angle) that the method also shows "
       << "above 1 within " << kHighlightRadiusDegrees << " degrees; precision, the share of "
       << "its own that lie as near a true one (docs/metrics.md); mean +- std over the envmaps "
       << "that have any (how many, of all, in brackets):\n\n"
       << "| method | highlight recall | highlight precision |\n|---|---|---|\n";
    for (const auto& m : methods)
        md << "| " << m.name << " | " << countedCell(m.highlightRecall, 2) << " | "
           << countedCell(m.highlightPrecision, 2) << " |\n";
    return md.str();
}

std::string headroomTableMarkdown(const MethodScores& ours, const std::vector<MethodScores>& rows) {
    std::ostringstream md;
    md << "\nHeadroom: ours with one part of the truth put in, so each row says what a perfect "
          "job on that part alone would give (lamps and windows: the pixels whose true "
          "luminance is above 1; turned: put in that many degrees to the side, about the "
          "vertical axis, so the row says what placing them that far off would give):\n\n"
       << "| method | PSNR all (dB) | angular all (deg) | irradiance rel. error | radiance ratio "
          "|\n|---|---|---|---|---|\n";
    const auto line = [&](const MethodScores& m) {
        md << "| " << m.name << " | " << cell(m.psnrAll, 2) << " | " << cell(m.angularAll, 2)
           << " | " << cell(m.irradianceError, 3) << " | " << cell(m.radianceRatio, 2) << " |\n";
    };
    line(ours);
    for (const MethodScores& m : rows) line(m);
    return md.str();
}

ImageRGB sheetStrip(const std::vector<ImageRGB>& row) {
    return contactSheet({row}, kEvalSheetTileHeight, kSheetGap);
}

ImageRGB stackSheetStrips(const std::vector<ImageRGB>& strips) {
    if (strips.empty()) throw InputError("contact sheet: nothing to show");
    int width = 0;
    for (const ImageRGB& s : strips) width = std::max(width, s.width);
    const int pitch = kEvalSheetTileHeight + kSheetGap;
    ImageRGB sheet(width, kSheetGap + int(strips.size()) * pitch);
    std::fill(sheet.pixels.begin(), sheet.pixels.end(), 0.02f);  // contactSheet's border
    for (std::size_t r = 0; r < strips.size(); ++r) {
        const ImageRGB& s = strips[r];
        if (s.height != pitch + kSheetGap)
            throw FileError("contact sheet strip of the wrong height");
        for (int y = 0; y < s.height; ++y)
            for (int x = 0; x < s.width; ++x)
                std::copy(s.at(x, y), s.at(x, y) + 3, sheet.at(x, int(r) * pitch + y));
    }
    return sheet;
}

std::string evalPredictionNotes(double highlightGain, double highlightKnee, bool shell,
                                bool unclippedPhotos) {
    std::ostringstream notes;
    if (highlightGain != 1.0 && highlightKnee == 1.0)
        notes << "\n\"ours\": what each predicted voxel holds above white, times " << highlightGain
              << " (`--highlight-gain`).\n";
    else if (highlightGain != 1.0)
        notes << "\n\"ours\": what each predicted voxel holds above luminance " << highlightKnee
              << ", times " << highlightGain << " (`--highlight-gain`, `--highlight-knee`).\n";
    if (shell)
        notes << "\n\"ours\": what each predicted volume's camera did not see collapsed into an "
                 "opaque shell (the default of `--shell`; `--no-shell` scores the fog; "
                 "docs/network.md).\n";
    if (unclippedPhotos)
        notes << "\n\"ours\": predicted from each example's linear renders (ref.exr, src.exr), "
                 "not its PNG photos (`--unclipped-photos`).\n";
    return notes.str();
}

std::string mergeEvalShards(const std::string& dir) {
    const fs::path table = fs::path(dir) / "table.md";
    if (fs::exists(table))
        throw FileError("'" + dir +
                        "' is merged already (it holds table.md); remove table.md to merge again");
    const std::vector<nlohmann::json> records = readShardSet(dir, "eval", {"eval"});
    const nlohmann::json& header = records.front()["eval"];
    const std::size_t scenes = header.value("scenes", std::size_t(0));

    // Every scene's rows, from the shard that owns it, in the order of the one run.
    std::vector<std::vector<EvalCsvRow>> rowsByScene(scenes);
    std::vector<bool> seen(scenes, false);
    std::vector<std::pair<std::size_t, fs::path>> strips;  // (scene, file), each shard's first rows
    for (const nlohmann::json& r : records) {
        const std::string csvName = r.value("csv", "");
        const fs::path csvPath = fs::path(dir) / csvName;
        if (csvName.empty()) throw FileError("shard records in '" + dir + "' name no metrics file");
        std::map<std::string, std::size_t> sceneOf;
        for (const nlohmann::json& e : r["examples"]) {
            const std::size_t index = e.value("index", scenes);
            if (index >= scenes || seen[index])
                throw FileError("shard records in '" + dir + "' list scene " + e.value("id", "?") +
                                " out of place");
            seen[index] = true;
            sceneOf[e.value("id", "")] = index;
        }
        for (EvalCsvRow& row : readEvalCsv(csvPath.string())) {
            const auto it = sceneOf.find(row.example);
            if (it == sceneOf.end())
                throw FileError("'" + csvPath.string() + "' scores example '" + row.example +
                                "' its record lacks");
            rowsByScene[it->second].push_back(std::move(row));
        }
        for (const nlohmann::json& s : r["sheet_rows"])
            strips.push_back({s.value("scene", scenes), fs::path(dir) / s.value("file", "")});
    }
    for (std::size_t s = 0; s < scenes; ++s)
        if (!seen[s])
            throw FileError("shard records in '" + dir + "' lack scene " + std::to_string(s));

    std::vector<MethodScores> methods;
    for (const auto& name : header["methods"]) {
        methods.emplace_back();
        methods.back().name = name.get<std::string>();
    }
    std::ostringstream csv;
    csv << evalCsvHeader();
    for (const auto& rows : rowsByScene)
        for (const EvalCsvRow& row : rows) {
            std::size_t m = 0;
            while (m < methods.size() && methods[m].name != row.method) ++m;
            if (m == methods.size())
                throw FileError("eval shard in '" + dir + "' scores unknown method '" + row.method +
                                "'");
            addScores(methods[m], row.values);
            csv << evalCsvRow(row.example, row.envmap, row.method, row.values, false);
        }

    std::stable_sort(strips.begin(), strips.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<ImageRGB> sheet;
    for (std::size_t i = 0; i < std::min(kEvalSheetRows, strips.size()); ++i)
        sheet.push_back(readImage(strips[i].second.string()));

    const std::string markdown =
        evalTableMarkdown(methods, scenes, header.value("data", ""), header.value("config", "")) +
        evalPredictionNotes(header.value("highlight_gain", 1.0),
                            header.value("highlight_knee", 1.0), header.value("shell", false),
                            header.value("unclipped_photos", false));
    writeTextFile((fs::path(dir) / "metrics.csv").string(), csv.str());
    writePng(stackSheetStrips(sheet), (fs::path(dir) / "contact_sheet.png").string());
    writeTextFile(table.string(), markdown);
    return markdown;
}

}  // namespace lh::net
