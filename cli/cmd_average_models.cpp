// `lighthouse average-models A.pt B.pt [...] -o OUT.pt [--half]`: the uniform average of the
// weights of models fine-tuned from one model (net/model_average.h).
#include "cli/commands.h"
#include "cli/net_commands.h"
#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/path_guard.h"
#include "net/model_average.h"

#include <filesystem>
#include <iostream>

namespace lh::cli {

namespace {

struct AverageOptions {
    std::vector<std::string> models;
    std::string out;
    bool half = false, force = false;
};

void runAverage(const AverageOptions& o) {
    std::vector<NamedInput> inputs;
    for (const std::string& m : o.models) inputs.push_back({m, "a model to average"});
    requireOutputIsNotAnInput(o.out, "-o", inputs);
    requireWritableOutput(o.out);  // before the models are read, not after
    if (std::filesystem::exists(o.out) && !o.force)
        throw InputError("'" + o.out + "' exists: remove it, or pass --force to overwrite it");
    std::cerr << "average-models: averaging " << o.models.size() << " models\n";
    net::writeAveragedModel(o.models, o.out, o.half);
    std::cerr << "average-models: wrote " << o.out << (o.half ? " (half precision)" : "") << "\n";
}

}  // namespace

void addAverageModelsCommand(CLI::App& app) {
    auto o = std::make_shared<AverageOptions>();
    CLI::App* cmd = app.add_subcommand("average-models", netCommandDescription("average-models"));
    cmd->add_option("models", o->models,
                    "Two or more model files of one configuration, fine-tuned from one model "
                    "(a file named twice counts twice)")
        ->required()
        ->expected(-2);
    cmd->add_option("-o,--output", o->out, "Averaged model file (written atomically)")->required();
    cmd->add_flag("--half", o->half, "Store the average in half precision (half the size)");
    cmd->add_flag("--force", o->force, "Overwrite an existing output file");
    cmd->callback([o] { runAverage(*o); });
}

}  // namespace lh::cli
