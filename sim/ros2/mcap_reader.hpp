// Reads an MCAP file of our own code: through its summary and chunk indexes when it has them,
// else by a linear scan of its records. A recording cut off by a crash (no summary, the last
// record truncated) is read as far as it goes, with a warning that names the byte offset.
// Damaged bytes throw std::runtime_error "FILE: at byte N: problem"; every length is checked
// against the file before it is used.
#pragma once

#include "sim/ros2/compression.hpp"
#include "sim/ros2/mapped_file.hpp"
#include "sim/ros2/mcap_format.hpp"

#include <cstdint>
#include <functional>
#include <map>
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

class McapReader {
 public:
  explicit McapReader(const std::string& path);

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
  void forEachMessage(const std::set<std::uint16_t>& channel_ids, const std::function<void(const McapMessage&)>& visit) const;
  // The log times of these channels' messages, sorted, from the message indexes (no chunk is
  // decompressed); nothing when the file is not indexed (then read the messages).
  std::optional<std::vector<std::uint64_t>> indexedLogTimes(const std::set<std::uint16_t>& channel_ids) const;

 private:
  bool readSummary();
  void scanData();  // the linear pass of the constructor: schemas, channels, counts
  // The messages of the chunk record at file offset `at`, decompressed into `buffer`, sorted
  // by log time; those of `wanted` channels only (all when empty).
  std::vector<McapMessage> chunkMessages(std::uint64_t at, const std::set<std::uint16_t>& wanted,
                                         std::vector<std::uint8_t>& buffer) const;

  std::string path_;
  MappedFile file_;
  // One decompression context for every chunk read (a reader is used by one thread at a time).
  mutable Decompressor decompressor_;
  mutable std::vector<std::vector<std::uint8_t>> chunk_buffers_;  // see forEachMessage
  std::uint64_t data_end_ = 0;  // where the data section ends (the summary or the footer)
  std::map<std::uint16_t, mcap::Schema> schemas_;
  std::map<std::uint16_t, mcap::Channel> channels_;
  std::map<std::uint16_t, std::uint64_t> counts_;
  std::vector<mcap::ChunkIndex> chunk_indexes_;
  bool indexed_ = false;
  std::vector<std::string> warnings_;
};

// True when the file starts with MCAP's magic.
bool isMcapFile(const std::string& path);

}  // namespace bimloc::sim::ros2
