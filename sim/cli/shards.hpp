// Sweeps beyond one machine: `bimloc run ... --shard K/N` runs the K-th of N deterministic
// slices of the scenario list (after every expansion: --all-rooms x --seeds, --starts ...),
// and `bimloc report merge` puts the slices' JSON back together into the unsharded run's
// report. A slice is every N-th scenario from the K-th on (strided, not blocks: neighbours in
// the list, the seeds of one room, cost alike, so each slice gets its share of the slow ones).
// The engine that runs the slices is Slurm's job arrays or Kubernetes' Indexed Jobs (deploy/).
#pragma once

#include "sim/scenario/scenario.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace bimloc::cli {

struct ShardSpec {
  int index = 1;  // K, 1-based
  int count = 1;  // N
  bool contains(std::size_t scenario) const { return static_cast<int>(scenario % static_cast<std::size_t>(count)) == index - 1; }
};

// "K/N" with 1 <= K <= N; throws std::invalid_argument saying what is expected.
ShardSpec parseShard(const std::string& text);

// A fingerprint of the whole (unsharded) scenario list: shards of different sweeps differ.
// FNV-1a (64 bit) over what makes each scenario: name, world, storey, seed, duration, start,
// localizer settings, site, expectations.
std::string sweepFingerprint(const std::vector<sim::Scenario>& scenarios);

// The "shard" object a sharded run's JSON carries: index, count, the sweep's size and
// fingerprint, and the position of each of its scenarios in the unsharded list.
nlohmann::json shardJson(const ShardSpec& shard, std::size_t total, const std::string& fingerprint,
                         const std::vector<std::size_t>& positions);

// The unsharded report from the shards' reports (file name, parsed JSON): scenarios in the
// unsharded order, the summary recomputed (wall_seconds: the shards' sum). Throws
// std::runtime_error naming the file(s) for a report without shard metadata, shards of
// different sweeps or counts, a shard given twice, overlapping or missing shards.
nlohmann::json mergeShards(const std::vector<std::pair<std::string, nlohmann::json>>& shards);

}  // namespace bimloc::cli
