// Sharding batch work over many scenes (`synth`, `eval`, batch `predict`): `--shard K/N`
// (0-based) makes a run do item i of the whole list exactly when i mod N == K, so N runs,
// on one machine or as a Slurm job array, together do what one run does. Each shard writes
// a record, DIR/shard-K-of-N.json, beside its outputs; `lighthouse merge DIR` checks that
// every shard of the set is there and writes what the single run would have (manifests,
// tables, contact sheets).
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace lh {

struct Shard {
    int index = 0;  // K
    int count = 1;  // N
    bool active =
        false;  // --shard was given (even 0/1): write a shard record, not the merged outputs

    bool owns(std::size_t item) const { return item % std::size_t(count) == std::size_t(index); }
    std::string tag() const;         // "shard-K-of-N"
    std::string recordName() const;  // "shard-K-of-N.json"
};

// "K/N" with 0 <= K < N <= 100000; throws InputError naming the text otherwise.
Shard parseShard(const std::string& text);

// The records of one complete set of shards of `kind` ("synth", "eval", "predict") in
// `dir`, ordered by K. Throws FileError if there are none, if they disagree on N, on their
// kind or on `sameKeys` (the options every shard must share), or if any K of N is missing.
std::vector<nlohmann::json> readShardSet(const std::string& dir, const std::string& kind,
                                         const std::vector<std::string>& sameKeys);

// The kind ("synth", "eval", "predict") of the shard records in `dir`, or "" if none.
std::string shardKindIn(const std::string& dir);

}  // namespace lh
