// `lighthouse eval`: the paper's Table 2 on our synthetic test split. Per test envmap, four
// predictions are scored against the ground truth (CONVENTIONS.md metrics, all and observed
// content), and reported as mean +- std:
//   ours            the completed lighting volume, rendered by the C++ ray marcher;
//   MPI only        the MPI resampled onto the levels without completion; what it leaves
//                   unseen is filled with grey (sRGB 0.5), as in the paper's ablation;
//   global envmap   one envmap per scene, used at every point (DeepLight-like): the MPI seen
//                   from the reference camera, its unobserved directions filled with the mean
//                   of the observed content (the reference image's mean colour);
//   oracle          the scene's true geometry and light voxelised into the same layout, the
//                   ceiling of any predictor at this resolution (synth/oracle.h).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace lh::net {

struct EvalOptions {
    std::string data;        // test split (lighthouse synth --split test)
    std::string model;       // empty: the bundled model
    std::string out = "eval";  // directory: table.md, metrics.csv, contact_sheet.png
    int maxScenes = 0;       // 0: all
    bool oracle = true;
    std::string hdriDir;     // panoramas for the oracle's windows
    std::string device = "cpu";
    int threads = 0;
};

struct MethodScores {
    std::string name;
    std::vector<double> psnrAll, angularAll, psnrObserved, angularObserved;
};

struct EvalReport {
    std::vector<MethodScores> methods;
    std::string markdown;  // the table
};

EvalReport evaluate(const EvalOptions& options, std::ostream& progress);

}  // namespace lh::net
