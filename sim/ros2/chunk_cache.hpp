// The whole decompressed chunks that a pass over a few small topics (ReadPlan::kSmallTopics:
// odometry, tf, truth) keeps for the read of the other topics that follows it (the clouds'),
// so that a chunk whose records mix both (MCAP as `ros2 bag record` writes it: every topic in
// 768 KiB zstd chunks) is decompressed once instead of once by each pass.
//
// Bounded: the first chunks, in the order the reads reach them, up to a budget of decompressed
// bytes chosen from the chunk indexes before the pass starts (so which chunks are kept does not
// depend on the worker threads' timing); the chunks past it are decompressed by each pass, as
// without the cache. A kept chunk serves the next whole read once, and is dropped after it.
// Only compressed chunks are kept (an uncompressed chunk is read in place, for nothing), and
// only those with messages of other channels than the pass's.
#pragma once

#include "sim/ros2/mcap_format.hpp"

#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <vector>

namespace bimloc::sim::ros2 {

class ChunkCache {
 public:
  explicit ChunkCache(std::uint64_t budget_bytes) : budget_(budget_bytes) {}
  std::uint64_t budget() const { return budget_; }
  void setBudget(std::uint64_t budget_bytes) { budget_ = budget_bytes; }  // before a read, not during one
  // Which of `chunks` (a read's, in its order) a pass over `wanted` keeps: true for the first
  // compressed ones with messages of other channels, while their uncompressed sizes add up to
  // no more than the budget.
  std::vector<bool> choose(const std::vector<const mcap::ChunkIndex*>& chunks, const std::set<std::uint16_t>& wanted) const;
  // Thread-safe (the prefetch workers take, the reading thread puts).
  void put(std::uint64_t chunk_offset, std::vector<std::uint8_t>&& records);
  std::optional<std::vector<std::uint8_t>> take(std::uint64_t chunk_offset);
  void clear();
  std::size_t size() const;  // chunks held

 private:
  std::uint64_t budget_;
  mutable std::mutex mutex_;
  std::map<std::uint64_t, std::vector<std::uint8_t>> chunks_;  // by the Chunk record's file offset
};

// The budget of an MCAP reader's chunk cache: the environment's BIMLOC_MCAP_CACHE_MB (MiB; 0: no
// cache), else 256 MiB. Throws std::runtime_error naming the variable when it is not a number
// from 0 to 65536.
std::uint64_t defaultChunkCacheBytes();

}  // namespace bimloc::sim::ros2
