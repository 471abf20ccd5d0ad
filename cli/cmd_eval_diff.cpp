// `lighthouse eval-diff A B [--method NAME]`: the paired difference B - A, per metric, of two
// `lighthouse eval` runs over the same test set (net/eval_pairs.h), e.g. a new model against
// the bundled one. A and B are eval output folders (their metrics.csv) or metrics.csv files.
#include "cli/commands.h"
#include "core/errors.h"
#include "net/eval_pairs.h"

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

namespace lh::cli {

namespace {

namespace fs = std::filesystem;

struct EvalDiffOptions {
    std::string a, b;
    std::string method = "ours";
};

// DIR/metrics.csv for an eval's output folder, the path itself otherwise.
std::string metricsFile(const std::string& path) {
    if (fs::is_directory(path)) {
        const fs::path csv = fs::path(path) / "metrics.csv";
        if (!fs::is_regular_file(csv))
            throw FileError("'" + path +
                            "' holds no metrics.csv: give a folder `lighthouse eval -o` wrote, "
                            "or its metrics.csv");
        return csv.string();
    }
    if (!fs::is_regular_file(path))
        throw FileError("'" + path +
                        "' does not exist (give an eval output folder or its "
                        "metrics.csv)");
    return path;
}

}  // namespace

void addEvalDiffCommand(CLI::App& app) {
    auto o = std::make_shared<EvalDiffOptions>();
    CLI::App* cmd = app.add_subcommand(
        "eval-diff",
        "Paired difference B - A of two evals of the same envmaps, per metric, with its standard "
        "error (Markdown)");
    cmd->add_option("eval_a", o->a, "The first eval (A): its output folder or its metrics.csv")
        ->required();
    cmd->add_option("eval_b", o->b, "The second eval (B): the differences are B - A")->required();
    cmd->add_option("--method", o->method,
                    "The method's rows to pair (metrics.csv's third column: \"ours\", \"ours, MPI "
                    "only\", \"single global envmap\", \"oracle\")")
        ->capture_default_str();
    cmd->callback([o] {
        const std::string a = metricsFile(o->a), b = metricsFile(o->b);
        const auto diffs =
            net::pairedDifferences(net::readEvalCsv(a), net::readEvalCsv(b), o->method);
        std::cout << net::pairedDifferencesMarkdown(diffs, a, b, o->method);
    });
}

}  // namespace lh::cli
