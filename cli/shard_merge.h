// What batch `predict` writes into its output directory, shared by predict (which writes it
// in one run) and `lighthouse merge` (which writes it from a complete set of shards), so the
// two give the same bytes.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace lh::cli {

inline constexpr const char* kPredictionsIndex = "predictions.json";

// One pair's entry: its name, input files and output (relative to the output directory).
nlohmann::json predictionEntry(const std::string& name, const std::string& ref,
                               const std::string& src, const std::string& cameras,
                               const std::string& output);
// predictions.json: the model and every pair's entry, in the order of the list.
nlohmann::json predictionsIndex(const std::string& model, const nlohmann::json& entries);

}  // namespace lh::cli
