#include "study/memory_error.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace lh {
namespace {

// The storage target read from known rows: the default bound's row is judged, on disk and in
// memory, against a tenth of the dense size, and its loss against ground truth.
TEST(MemoryTarget, JudgesTheDefaultBoundsRow) {
    MemoryErrorRow unpruned, looser, atDefault;
    unpruned.setting = "unpruned", unpruned.tau = -1, unpruned.psnrGroundTruth = 20.0;
    looser.setting = "tau 0.1", looser.tau = 0.1, looser.diskBytesHalf = 1, looser.memoryBytes = 1;
    atDefault.setting = "tau 0.0001", atDefault.tau = 1e-4;
    atDefault.diskBytesHalf = 50'000, atDefault.memoryBytes = 300'000;  // 5% and 30% of 1 MB
    atDefault.psnrGroundTruth = 19.95, atDefault.lossDb = 0.05;
    const std::vector<MemoryErrorRow> rows{unpruned, atDefault, looser};
    std::string md = memoryTargetMarkdown(rows, 1e6, 1e-4);
    EXPECT_NE(md.find("on disk (Blosc, half precision): 0.05 MB, 5.0% of dense: **met**"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("in memory (OpenVDB grids): 0.3 MB, 30.0% of dense: **not met**"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("0.050 dB lost: **met**"), std::string::npos) << md;
    // Losing more than 0.1 dB fails the target; without ground truth it is not judged.
    std::vector<MemoryErrorRow> lossy = rows;
    lossy[1].lossDb = 0.2;
    EXPECT_NE(memoryTargetMarkdown(lossy, 1e6, 1e-4).find("0.200 dB lost: **not met**"),
              std::string::npos);
    lossy[1].psnrGroundTruth = -1;
    EXPECT_NE(memoryTargetMarkdown(lossy, 1e6, 1e-4).find("not measured without ground truth"),
              std::string::npos);
    // With rounded files measured (bench-sparsity --mantissa-bits), the rounded file is judged.
    std::vector<MemoryErrorRow> rounded = rows;
    rounded[1].mantissaBits = 7, rounded[1].diskBytesRounded = 120'000;
    EXPECT_NE(memoryTargetMarkdown(rounded, 1e6, 1e-4)
                  .find("on disk (Blosc, floats rounded to 7 mantissa bits): 0.12 MB, 12.0% of "
                        "dense: **not met**"),
              std::string::npos)
        << memoryTargetMarkdown(rounded, 1e6, 1e-4);
    // A run without a row at the bound says so.
    EXPECT_NE(memoryTargetMarkdown(rows, 1e6, 1e-3)
                  .find("not measured: this run has no row at that bound"),
              std::string::npos);
}

}  // namespace
}  // namespace lh
