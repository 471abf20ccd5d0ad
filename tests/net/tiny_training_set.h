// A training set small enough for unit tests: 3 synthetic examples of 64x48 with one 16x8
// envmap and an oracle volume in tinyHdrConfig()'s layout, baked coarsely (seconds, not
// minutes). Shared by the trainer, distributed-training and unclipped-photo suites.
#pragma once

#include "synth/dataset.h"
#include "tests/net/net_test_scenes.h"
#include "tests/support/temp_path.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace lh::test {

inline void writeTinyTrainingSet(const std::string& dir) {
    synth::SynthOptions o;
    o.count = 3;
    o.out = dir;
    o.width = 64;
    o.height = 48;
    o.envWidth = 16;
    o.envHeight = 8;
    o.envmapsPerExample = 1;
    o.supersample = 1;
    o.hdriDir = LIGHTHOUSE_HDRI_DIR;
    o.bake.texelSize = 0.4;
    o.bake.maxTexels = 2000;
    o.bake.gatherRays = 16;
    o.bake.lightSamples = 4;
    o.bake.bounces = 1;
    o.oracleLevels = tinyHdrConfig().levels;
    o.oracleResolution = tinyHdrConfig().resolution;
    synth::writeDataset(o);
}

// A test suite over one tiny training set (dataDir()), written before its first test and
// removed after its last.
class TinyTrainingSetTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dataDir() = uniqueTempPath("lighthouse_tiny_training_set");
        writeTinyTrainingSet(dataDir());
    }
    static void TearDownTestSuite() { std::filesystem::remove_all(dataDir()); }
    static std::string& dataDir() {
        static std::string path;
        return path;
    }
};

}  // namespace lh::test
