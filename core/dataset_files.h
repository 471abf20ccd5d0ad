// The files of one example directory of a data set (docs/synthetic_data.md): written by
// `lighthouse synth`, read by training, evaluation, `oracle`, `predict --examples`, `compare
// --batch` and `bench-sparsity --dataset`. The names live here alone, so that the writer and
// every reader agree.
#pragma once

#include <cstddef>
#include <string>

namespace lh::dataset {

inline constexpr const char* kCameras = "cameras.json";  // cameras, depth range, envmap points
inline constexpr const char* kScene = "scene.json";      // the synthetic scene (synth/scene_json.h)
inline constexpr const char* kOracle = "oracle.vdb";     // the oracle lighting volume
inline constexpr const char* kDepth = "depth.exr";       // the reference view's z-depth, metres
// The same depth as rooms rendered by Blender Cycles name it (read first when both exist).
inline constexpr const char* kCyclesDepth = "ref_depth.exr";

// The views "ref", "src" and "tgt" (the keys of cameras.json): sRGB PNG and linear EXR.
inline std::string viewPng(const std::string& view) { return view + ".png"; }
inline std::string viewExr(const std::string& view) { return view + ".exr"; }

// Envmap k is env_<k>.exr (linear; .png beside it, sRGB); beside it, by its stem: the observed
// mask <stem>_mask.png and the first-hit positions <stem>_pos.exr.
inline std::string envmapStem(std::size_t k) { return "env_" + std::to_string(k); }
inline std::string envmapExr(std::size_t k) { return envmapStem(k) + ".exr"; }
inline std::string envmapPng(std::size_t k) { return envmapStem(k) + ".png"; }
inline std::string maskPng(const std::string& envmapStem) { return envmapStem + "_mask.png"; }
inline std::string positionsExr(const std::string& envmapStem) { return envmapStem + "_pos.exr"; }
// A file name that is an envmap (not its mask nor its positions), as a regular expression.
inline constexpr const char* kEnvmapExrPattern = R"(env_[0-9]+\.exr)";

}  // namespace lh::dataset
