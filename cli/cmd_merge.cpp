// `lighthouse merge DIR...`: joins what the shards of a batch command (`--shard K/N`, core/shard.h)
// wrote into DIR, once all N are done: a data set's manifest.json and contact sheet (synth),
// table.md, metrics.csv and contact sheet (eval), predictions.json (batch predict).
#include "cli/commands.h"
#include "cli/shard_merge.h"
#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/shard.h"
#include "net/eval_table.h"
#include "synth/dataset.h"

#include <filesystem>
#include <iostream>

namespace lh::cli {

namespace fs = std::filesystem;

nlohmann::json predictionEntry(const std::string& name, const std::string& ref,
                               const std::string& src, const std::string& cameras,
                               const std::string& output) {
    return {{"name", name}, {"ref", ref}, {"src", src}, {"cameras", cameras}, {"output", output}};
}

nlohmann::json predictionsIndex(const std::string& model, const nlohmann::json& entries) {
    return {{"model", model}, {"predictions", entries}};
}

namespace {

std::size_t mergePredictShards(const std::string& dir) {
    const fs::path index = fs::path(dir) / kPredictionsIndex;
    if (fs::exists(index))
        throw FileError("'" + dir + "' is merged already (it holds " + kPredictionsIndex +
                        "); remove it to merge again");
    const std::vector<nlohmann::json> records = readShardSet(dir, "predict", {"predict"});
    const nlohmann::json& header = records.front()["predict"];
    const std::size_t count = header.value("pairs", std::size_t(0));
    nlohmann::json entries = nlohmann::json::array();
    for (std::size_t i = 0; i < count; ++i) entries.push_back(nullptr);
    for (const nlohmann::json& r : records)
        for (nlohmann::json e : r["items"]) {
            const std::size_t i = e.value("index", count);
            if (i >= count || !entries[i].is_null())
                throw FileError("shard records in '" + dir + "' list pair " + e.value("name", "?") +
                                " out of place");
            if (!fs::is_regular_file(fs::path(dir) / e.value("output", "")))
                throw FileError("'" + (fs::path(dir) / e.value("output", "")).string() +
                                "', listed by a shard record, is missing");
            e.erase("index");
            e.erase("seconds");
            entries[i] = e;
        }
    for (std::size_t i = 0; i < count; ++i)
        if (entries[i].is_null())
            throw FileError("shard records in '" + dir + "' lack pair " + std::to_string(i));
    writeTextFile(index.string(), predictionsIndex(header.value("model", ""), entries).dump(1));
    return count;
}

void runMerge(const std::vector<std::string>& dirs) {
    for (const std::string& dir : dirs) {
        if (!fs::is_directory(dir)) throw FileError("'" + dir + "' is not a directory");
        const std::string kind = shardKindIn(dir);
        if (kind == "synth") {
            const int n = synth::mergeDatasetShards(dir);
            std::cerr << "merge: " << dir << ": " << n
                      << " examples -> manifest.json, contact_sheet.png\n";
        } else if (kind == "eval") {
            std::cout << net::mergeEvalShards(dir);
            std::cerr << "merge: " << dir << " -> table.md, metrics.csv, contact_sheet.png\n";
        } else if (kind == "predict") {
            const std::size_t n = mergePredictShards(dir);
            std::cerr << "merge: " << dir << ": " << n << " pairs -> " << kPredictionsIndex << "\n";
        } else if (kind.empty()) {
            throw FileError(
                "'" + dir +
                "' holds no shard records (shard-K-of-N.json from synth, eval or predict --shard)");
        } else {
            throw FileError("'" + dir + "': unknown kind of shard record '" + kind + "'");
        }
    }
}

}  // namespace

void addMergeCommand(CLI::App& app) {
    auto dirs = std::make_shared<std::vector<std::string>>();
    CLI::App* cmd = app.add_subcommand("merge",
                                       "Join the outputs of a complete set of shards (synth, eval "
                                       "or predict --shard K/N) in each DIR");
    cmd->add_option("dirs", *dirs,
                    "Directories the shards wrote into (synth -o, eval -o, predict -o)")
        ->required();
    cmd->footer(
        "Refuses an incomplete set (names the missing shards), records that disagree, and a "
        "directory merged "
        "already. synth: manifest.json (\"seconds\": the shards' sum) and contact_sheet.png; eval: "
        "table.md, "
        "metrics.csv, contact_sheet.png; predict: predictions.json. Everything but the timings is "
        "what one "
        "run without --shard writes.");
    cmd->callback([dirs] { runMerge(*dirs); });
}

}  // namespace lh::cli
