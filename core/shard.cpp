#include "core/shard.h"

#include "core/errors.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>

namespace lh {

namespace fs = std::filesystem;

std::string Shard::tag() const {
    return "shard-" + std::to_string(index) + "-of-" + std::to_string(count);
}

std::string Shard::recordName() const { return tag() + ".json"; }

Shard parseShard(const std::string& text) {
    static const std::regex form(R"(([0-9]{1,6})/([0-9]{1,6}))");
    std::smatch m;
    if (!std::regex_match(text, m, form))
        throw InputError("--shard must be K/N with 0 <= K < N (shard K of N, 0-based), got '" +
                         text + "'");
    Shard s;
    s.index = std::stoi(m[1].str());
    s.count = std::stoi(m[2].str());
    s.active = true;
    if (s.count < 1 || s.count > 100000 || s.index >= s.count)
        throw InputError(
            "--shard must be K/N with 0 <= K < N <= 100000 (shard K of N, 0-based), got '" + text +
            "'");
    return s;
}

namespace {

const std::regex kRecordName(R"(shard-([0-9]+)-of-([0-9]+)\.json)");

std::vector<fs::path> recordFiles(const std::string& dir) {
    std::vector<fs::path> out;
    if (!fs::is_directory(dir)) return out;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (entry.is_regular_file() && std::regex_match(name, kRecordName))
            out.push_back(entry.path());
    }
    std::sort(out.begin(), out.end());
    return out;
}

nlohmann::json readRecord(const fs::path& path) {
    std::ifstream in(path);
    if (!in) throw FileError("cannot read shard record '" + path.string() + "'");
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw FileError("shard record '" + path.string() + "' is not valid JSON: " + e.what());
    }
}

}  // namespace

std::string shardKindIn(const std::string& dir) {
    const auto files = recordFiles(dir);
    if (files.empty()) return "";
    return readRecord(files.front()).value("kind", "");
}

std::vector<nlohmann::json> readShardSet(const std::string& dir, const std::string& kind,
                                         const std::vector<std::string>& sameKeys) {
    if (!fs::is_directory(dir)) throw FileError("'" + dir + "' is not a directory");
    const auto files = recordFiles(dir);
    if (files.empty()) throw FileError("'" + dir + "' holds no shard records (shard-K-of-N.json)");
    std::map<int, nlohmann::json> byIndex;
    int count = -1;
    for (const fs::path& file : files) {
        nlohmann::json r = readRecord(file);
        if (r.value("kind", "") != kind)
            throw FileError("shard record '" + file.string() + "' is of kind '" +
                            r.value("kind", "") + "', not '" + kind + "'");
        const int k = r.value("shard", -1), n = r.value("shards", -1);
        if (n < 1 || k < 0 || k >= n ||
            file.filename().string() !=
                "shard-" + std::to_string(k) + "-of-" + std::to_string(n) + ".json")
            throw FileError("shard record '" + file.string() + "' does not match its name");
        if (count >= 0 && n != count)
            throw FileError("'" + dir + "' mixes shard records of " + std::to_string(count) +
                            " and " + std::to_string(n) + " shards; remove the stale ones");
        count = n;
        if (!byIndex.empty())
            for (const std::string& key : sameKeys)
                if (r.value(key, nlohmann::json()) !=
                    byIndex.begin()->second.value(key, nlohmann::json()))
                    throw FileError("shard records in '" + dir + "' disagree on '" + key + "' (" +
                                    files.front().filename().string() + " and " +
                                    file.filename().string() + ")");
        byIndex[k] = std::move(r);
    }
    if (int(byIndex.size()) != count) {
        std::string missing;
        int shown = 0;
        for (int k = 0; k < count && shown < 10; ++k)
            if (!byIndex.count(k)) {
                missing += (missing.empty() ? "" : ", ") + std::to_string(k);
                ++shown;
            }
        if (count - int(byIndex.size()) > shown) missing += ", ...";
        throw FileError("incomplete set of shards in '" + dir +
                        "': " + std::to_string(byIndex.size()) + " of " + std::to_string(count) +
                        " done, missing shard " + missing);
    }
    std::vector<nlohmann::json> out;
    for (auto& [k, r] : byIndex) out.push_back(std::move(r));
    return out;
}

}  // namespace lh
