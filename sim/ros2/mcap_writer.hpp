// Writes an MCAP file as rosbag2_storage_mcap does: profile "ros2", messages in chunks
// (zstd, lz4 or none), a MessageIndex per channel after each chunk, and a summary (schemas,
// channels, statistics, chunk indexes) with summary offsets, so a reader seeks instead of scanning.
#pragma once

#include "sim/ros2/mcap_format.hpp"

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace bimloc::sim::ros2 {

struct McapWriterOptions {
  std::string compression = "zstd";          // "zstd", "lz4" or "" (none)
  std::size_t chunk_bytes = 4u << 20;        // a chunk is closed once its records pass this size
  bool summary = true;                       // false: no summary (as a recording cut by a crash)
  std::string profile = "ros2", library = "bimloc";
};

class McapWriter {
 public:
  // Creates `path`; throws std::runtime_error naming it.
  McapWriter(const std::string& path, McapWriterOptions options = {});
  ~McapWriter();  // closes the file if still open, without the summary (the caller discards it)
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  std::uint16_t addSchema(const std::string& name, const std::string& encoding, const std::string& data);
  std::uint16_t addChannel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                           const std::map<std::string, std::string>& metadata = {});
  void write(std::uint16_t channel_id, std::uint64_t log_time_ns, std::uint64_t publish_time_ns, const std::uint8_t* data,
             std::size_t size);
  void write(std::uint16_t channel_id, std::uint64_t log_time_ns, const std::vector<std::uint8_t>& data) {
    write(channel_id, log_time_ns, log_time_ns, data.data(), data.size());
  }
  // Writes the last chunk, the summary and the footer. Throws std::runtime_error naming the file.
  void close();

  std::uint64_t messageCount(std::uint16_t channel_id) const;

 private:
  void flushChunk();
  void put(const std::vector<std::uint8_t>& bytes);

  std::string path_;
  McapWriterOptions options_;
  std::FILE* file_ = nullptr;
  std::uint64_t offset_ = 0;  // bytes written so far
  std::map<std::uint16_t, mcap::Schema> schemas_;
  std::map<std::uint16_t, mcap::Channel> channels_;
  std::map<std::uint16_t, std::uint64_t> counts_;
  std::map<std::uint16_t, std::uint32_t> sequence_;
  std::vector<mcap::ChunkIndex> chunk_indexes_;
  // The open chunk: its records, and per channel (log_time, offset in the records).
  std::vector<std::uint8_t> chunk_;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::uint64_t first_time_ = 0, last_time_ = 0, messages_ = 0;
};

}  // namespace bimloc::sim::ros2
