#include "sim/ros2/chunk_cache.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace bimloc::sim::ros2 {

std::vector<bool> ChunkCache::choose(const std::vector<const mcap::ChunkIndex*>& chunks, const std::set<std::uint16_t>& wanted) const {
  std::vector<bool> keep(chunks.size(), false);
  std::uint64_t held = 0;
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    const mcap::ChunkIndex& ci = *chunks[i];
    bool others = false;
    for (const auto& [channel, offset] : ci.message_index_offsets) others = others || !wanted.count(channel);
    if (ci.compression.empty() || !others) continue;
    if (ci.uncompressed_size > budget_ - held) break;  // the first ones only: the next read needs them first
    held += ci.uncompressed_size;
    keep[i] = true;
  }
  return keep;
}

void ChunkCache::put(std::uint64_t chunk_offset, std::vector<std::uint8_t>&& records) {
  std::lock_guard<std::mutex> lock(mutex_);
  chunks_[chunk_offset] = std::move(records);
}

std::optional<std::vector<std::uint8_t>> ChunkCache::take(std::uint64_t chunk_offset) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = chunks_.find(chunk_offset);
  if (it == chunks_.end()) return std::nullopt;
  std::vector<std::uint8_t> records = std::move(it->second);
  chunks_.erase(it);
  return records;
}

void ChunkCache::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  chunks_.clear();
}

std::size_t ChunkCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return chunks_.size();
}

std::uint64_t defaultChunkCacheBytes() {
  const char* env = std::getenv("BIMLOC_MCAP_CACHE_MB");
  if (!env || !*env) return std::uint64_t{256} << 20;
  char* end = nullptr;
  const unsigned long long n = std::strtoull(env, &end, 10);
  if (*end != '\0' || n > 65536)
    throw std::runtime_error(std::string("BIMLOC_MCAP_CACHE_MB=") + env + ": not a number of MiB from 0 to 65536");
  return static_cast<std::uint64_t>(n) << 20;
}

}  // namespace bimloc::sim::ros2
