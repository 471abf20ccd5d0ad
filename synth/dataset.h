// Synthetic data sets: per example a stereo pair, a held-out view, ground-truth
// envmaps at points where a user would insert an object, the reference depth map, an
// observed-content mask per envmap, cameras.json and scene.json. Deterministic by seed.
//
// Layout of DIR (one split per directory):
//   manifest.json                 generator version, split, seeds, sizes, examples, timings
//   contact_sheet.png             ref | src | env_0 of the first examples
//   000000/ ref.exr ref.png src.exr src.png tgt.exr tgt.png depth.exr
//           env_<k>.exr env_<k>.png env_<k>_mask.png env_<k>_pos.exr cameras.json scene.json
//           [oracle.vdb]                  with --oracle: the voxelised true scene (half floats)
#pragma once

#include "core/shard.h"
#include "synth/radiance_field.h"
#include "synth/scene_generator.h"

#include <cstdint>
#include <functional>
#include <string>

namespace lh::synth {

struct SynthOptions {
    uint64_t seed = 0;  // first example's index; example i uses seed + i
    int count = 10;
    std::string out;
    std::string split = "train";          // "train" or "test": disjoint seeds (even / odd)
    int width = 320, height = 240;        // views
    int envWidth = 240, envHeight = 120;  // envmaps
    int envmapsPerExample = 2;
    int supersample = 2;  // per axis, for views and envmaps
    std::string hdriDir;
    LampLayout lampLayout = LampLayout::Random;  // where the ceiling lights go
    BakeOptions bake;
    // The oracle lighting volume (oracle.h) per example as oracle.vdb, in the layout of the
    // example's far depth with this many levels of oracleResolution^3 (0: none). It is the
    // target of the network's direct (voxel) supervision.
    int oracleLevels = 0;
    int oracleResolution = 64;
    // With shard.active: only the examples i with shard.owns(i), and a shard record
    // (core/shard.h) instead of manifest.json and contact_sheet.png; mergeDatasetShards
    // writes those once every shard is done.
    Shard shard;

    void validate() const;  // throws InputError / ResourceError
};

// Seed of example `index` of a split: even for train, odd for test, so splits never share.
uint64_t exampleSeed(const std::string& split, uint64_t index);

struct ExampleSummary {
    std::string id;
    uint64_t seed = 0;  // the scene seed that was accepted
    int rejected = 0;   // scenes rejected before it (camera too close, facing a wall...)
    double seconds = 0;
    std::size_t texels = 0;
};

// Writes one example into `directory` (created atomically: a temporary name, then rename).
ExampleSummary writeExample(uint64_t seed, const std::string& directory,
                            const SynthOptions& options, PanoramaLibrary& panoramas);

// Writes `count` examples, skipping ones already complete (so an interrupted run resumes),
// then the manifest and a contact sheet. `progress(done, total, secondsSoFar)` after each.
void writeDataset(const SynthOptions& options,
                  const std::function<void(int, int, double)>& progress = {});

// The merge of a complete set of synth shards written into `dir`: manifest.json (its
// examples in order; "seconds" is the shards' sum) and contact_sheet.png, as one run would
// have written them. Throws FileError if a shard is missing, the records disagree, or
// `dir` was merged already (it holds manifest.json). Returns the number of examples.
int mergeDatasetShards(const std::string& dir);

}  // namespace lh::synth
