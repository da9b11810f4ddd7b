// Reads an MCAP file of our own code: through its summary and chunk indexes when it has them,
// else by a linear scan of its records. A recording cut off by a crash (no summary, the last
// record truncated) is read as far as it goes, with a warning that names the byte offset.
// Damaged bytes throw std::runtime_error "FILE: at byte N: problem"; every length is checked
// against the file before it is used.
#pragma once

#include "sim/ros2/compression.hpp"
#include "sim/ros2/mapped_file.hpp"
#include "sim/ros2/mcap_format.hpp"
#include "sim/ros2/read_plan.hpp"

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace bimloc::sim::ros2 {

struct McapMessage {
  const mcap::Channel* channel = nullptr;
  std::uint32_t sequence = 0;
  std::uint64_t log_time_ns = 0, publish_time_ns = 0;
  const std::uint8_t* data = nullptr;  // valid during the visit only
  std::size_t size = 0;
};

struct LoadedChunk;
class BufferPool;

class McapReader {
 public:
  explicit McapReader(const std::string& path);
  ~McapReader();
  McapReader(const McapReader&) = delete;
  McapReader& operator=(const McapReader&) = delete;

  const std::string& path() const { return path_; }
  const std::map<std::uint16_t, mcap::Schema>& schemas() const { return schemas_; }
  const std::map<std::uint16_t, mcap::Channel>& channels() const { return channels_; }
  const mcap::Schema* schemaOf(const mcap::Channel& c) const;
  // Messages per channel: the summary's Statistics, else counted by the scan.
  const std::map<std::uint16_t, std::uint64_t>& messageCounts() const { return counts_; }
  bool indexed() const { return indexed_; }  // read through the summary's chunk indexes
  // "FILE: ..." lines: a truncated recording, a summary that could not be used.
  const std::vector<std::string>& warnings() const { return warnings_; }

  // Calls `visit` for the messages of `channel_ids` (every channel when empty) in log-time order
  // (indexed; a linear scan keeps the file's order of chunks, each chunk sorted by log time).
  // The same messages whatever the plan (read_plan.hpp), which says how the chunks are read:
  // - kAll: decompressed ahead on the worker threads (setPrefetch) from the first chunk on;
  // - kSmallTopics: the same, but a chunk is decompressed only as far as its last message of
  //   these channels (its message indexes say where; the chunk's CRC is then left to a pass
  //   that reads it whole); a chunk whose indexes do not match what its prefix holds, or whose
  //   prefix is damaged, is read whole;
  // - kFirst: each chunk decompressed on the calling thread when the read reaches it (nothing
  //   ahead: the visit is about to stop, by throwing). The chunk it stops in (whole,
  //   CRC-checked; the only one it then holds) is kept, and the next kAll read of the same
  //   channels takes it instead of decompressing it again. The kept chunk serves that one read.
  void forEachMessage(const std::set<std::uint16_t>& channel_ids, const std::function<void(const McapMessage&)>& visit,
                      ReadPlan plan = ReadPlan::kAll) const;
  // Chunks decompressed ahead on a worker thread by forEachMessage (chunk_prefetcher.hpp; 0:
  // none, every chunk decompressed on the reading thread). The messages are the same either way.
  // `workers` threads decompress them (several chunks at once when more than 1).
  void setPrefetch(std::size_t chunks, std::size_t workers = 1);
  std::size_t prefetchChunks() const { return prefetch_chunks_; }
  // How many chunks the reads so far have loaded (decompressed, or read in place, and indexed).
  std::uint64_t chunkLoads() const { return chunk_loads_.load(std::memory_order_relaxed); }
  // How many times the reads so far have decompressed a compressed chunk, whole or a prefix.
  std::uint64_t chunkDecompressions() const { return decompressions_.load(std::memory_order_relaxed); }
  // The log times of these channels' messages, sorted, from the message indexes (no chunk is
  // decompressed); nothing when the file is not indexed (then read the messages).
  std::optional<std::vector<std::uint64_t>> indexedLogTimes(const std::set<std::uint16_t>& channel_ids) const;

 private:
  bool readSummary();
  void scanData();  // the linear pass of the constructor: schemas, channels, counts
  // The messages of the chunk record at file offset `at`, decompressed by `z` into `chunk`'s
  // buffer, sorted by log time; those of `wanted` channels only (all when empty). Reads only
  // what no read changes (the file, the channels): safe on the prefetch worker.
  // Only the records in the chunk's first `prefix` bytes when it is less than the chunk's size.
  // Returns how many messages it kept.
  std::size_t chunkMessages(std::uint64_t at, const std::set<std::uint16_t>& wanted, Decompressor& z, LoadedChunk& chunk,
                            std::uint64_t prefix = UINT64_MAX) const;
  // Where the chunk's records after its last message of `wanted` start (UINT64_MAX: it is the
  // last, or the indexes cannot tell), and how many messages of `wanted` it has.
  std::uint64_t wantedPrefix(const mcap::ChunkIndex& ci, const std::set<std::uint16_t>& wanted, std::size_t& count) const;
  // The (log_time, offset in the chunk) pairs of the MessageIndex record at `offset`.
  std::vector<std::pair<std::uint64_t, std::uint64_t>> messageIndexEntries(std::uint64_t offset, std::uint16_t channel) const;

  std::string path_;
  MappedFile file_;
  Decompressor decompressor_;  // the constructor's linear scan's
  std::size_t prefetch_chunks_ = 0, prefetch_workers_ = 1;
  // The chunks' buffers, handed from pass to pass (chunk_prefetcher.hpp): as many as one pass
  // holds at once (the chunks ahead, the one being read, one overlapping it).
  std::unique_ptr<BufferPool> buffers_;
  std::uint64_t data_end_ = 0;  // where the data section ends (the summary or the footer)
  std::map<std::uint16_t, mcap::Schema> schemas_;
  std::map<std::uint16_t, mcap::Channel> channels_;
  std::map<std::uint16_t, std::uint64_t> counts_;
  std::vector<mcap::ChunkIndex> chunk_indexes_;
  bool indexed_ = false;
  std::vector<std::string> warnings_;
  struct KeptChunk;  // the chunk a kFirst read stopped in, and the channels it holds the messages of
  mutable std::unique_ptr<KeptChunk> kept_;
  mutable std::mutex kept_mutex_;
  mutable std::atomic<std::uint64_t> chunk_loads_{0}, decompressions_{0};
};

// True when the file starts with MCAP's magic.
bool isMcapFile(const std::string& path);

}  // namespace bimloc::sim::ros2
