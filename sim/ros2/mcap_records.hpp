// MCAP's records as the reader parses them (mcap_format.hpp has their layout): a walk over a
// run of records that stops where one is cut short, and the parsing of the records whose
// fields bimloc uses. Every length is checked (ByteCursor); errors name the file and the offset.
#pragma once

#include "sim/ros2/byte_cursor.hpp"
#include "sim/ros2/compression.hpp"
#include "sim/ros2/mcap_format.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sim::ros2::mcap {

// `visit(opcode, content, offset of the record)` returns false to stop.
using RecordVisitor = std::function<bool(std::uint8_t opcode, ByteCursor& content, std::uint64_t at)>;

// Walks the records of data[0, size) (`base`: the offset of data[0] in the file, or in the
// chunk). Returns where a record is cut short (the data ends inside it), or nothing when every
// record is whole.
std::optional<std::uint64_t> walkRecords(const std::uint8_t* data, std::size_t size, std::uint64_t base,
                                         const std::string& where, const RecordVisitor& visit);

Schema parseSchema(ByteCursor& c);
Channel parseChannel(ByteCursor& c);
ChunkIndex parseChunkIndex(ByteCursor& c);

struct ChunkHeader {  // a Chunk record's fields; `records` points into the file
  std::uint64_t start = 0, end = 0, uncompressed_size = 0;
  std::uint32_t crc = 0;
  std::string compression;
  const std::uint8_t* records = nullptr;
  std::uint64_t records_size = 0, records_at = 0;
};
ChunkHeader parseChunk(ByteCursor& c);

// The chunk's records, decompressed by `z` into `buffer` (the records in the file themselves
// when the chunk is not compressed: no copy) and checked against their CRC (when it is not 0).
// With `prefix` below the chunk's size, only its first `prefix` bytes (whole records, for a
// reader that needs only those): the CRC, which needs every byte, is then not checked.
// The bytes returned are valid while `buffer` and the file are.
struct ChunkRecords {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};
ChunkRecords inflate(const ChunkHeader& h, const std::string& where, Decompressor& z, std::vector<std::uint8_t>& buffer,
                     std::uint64_t prefix = UINT64_MAX);

}  // namespace bimloc::sim::ros2::mcap
