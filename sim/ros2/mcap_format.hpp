// MCAP (https://mcap.dev/spec), the container of ROS 2 bags since Iron: its magic, record
// opcodes, and the records bimloc keeps. Everything little endian; strings and maps carry a
// uint32 length, a record a uint8 opcode and a uint64 length.
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace bimloc::sim::ros2::mcap {

inline constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};
inline constexpr std::size_t kRecordHeaderBytes = 9;                    // opcode + length
inline constexpr std::size_t kFooterBytes = kRecordHeaderBytes + 20;    // summary_start, summary_offset_start, crc

enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

struct Schema {
  std::uint16_t id = 0;
  std::string name, encoding, data;  // ROS 2: "ros2msg", the .msg text
};

struct Channel {
  std::uint16_t id = 0, schema_id = 0;
  std::string topic, message_encoding;  // ROS 2: "cdr"
  std::map<std::string, std::string> metadata;  // rosbag2: offered_qos_profiles
};

struct ChunkIndex {
  std::uint64_t message_start_time = 0, message_end_time = 0;
  std::uint64_t chunk_start_offset = 0, chunk_length = 0;
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;
  std::uint64_t message_index_length = 0;
  std::string compression;
  std::uint64_t compressed_size = 0, uncompressed_size = 0;
};

}  // namespace bimloc::sim::ros2::mcap
