#include "sim/ros2/mcap_records.hpp"

#include "sim/ros2/compression.hpp"
#include "sim/ros2/crc32.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace bimloc::sim::ros2::mcap {

std::optional<std::uint64_t> walkRecords(const std::uint8_t* data, std::size_t size, std::uint64_t base,
                                         const std::string& where, const RecordVisitor& visit) {
  std::size_t pos = 0;
  while (pos < size) {
    if (size - pos < kRecordHeaderBytes) return base + pos;
    const std::uint8_t opcode = data[pos];
    std::uint64_t length;
    std::memcpy(&length, data + pos + 1, 8);
    if (length > size - pos - kRecordHeaderBytes) return base + pos;
    ByteCursor content(data + pos + kRecordHeaderBytes, static_cast<std::size_t>(length), where,
                       base + pos + kRecordHeaderBytes);
    if (!visit(opcode, content, base + pos)) return std::nullopt;
    pos += kRecordHeaderBytes + static_cast<std::size_t>(length);
  }
  return std::nullopt;
}

Schema parseSchema(ByteCursor& c) {
  Schema s;
  s.id = c.u16("Schema id");
  s.name = c.string("Schema name");
  s.encoding = c.string("Schema encoding");
  const std::uint32_t n = c.u32("Schema data");
  s.data.assign(reinterpret_cast<const char*>(c.bytes(n, "Schema data")), n);
  return s;
}

Channel parseChannel(ByteCursor& c) {
  Channel ch;
  ch.id = c.u16("Channel id");
  ch.schema_id = c.u16("Channel schema_id");
  ch.topic = c.string("Channel topic");
  ch.message_encoding = c.string("Channel message_encoding");
  ch.metadata = c.stringMap("Channel metadata");
  return ch;
}


ChunkHeader parseChunk(ByteCursor& c) {
  ChunkHeader h;
  h.start = c.u64("Chunk message_start_time");
  h.end = c.u64("Chunk message_end_time");
  h.uncompressed_size = c.u64("Chunk uncompressed_size");
  h.crc = c.u32("Chunk uncompressed_crc");
  h.compression = c.string("Chunk compression");
  h.records_size = c.u64("Chunk records length");
  h.records_at = c.fileOffset();
  h.records = c.bytes(h.records_size, "Chunk records");
  return h;
}

ChunkRecords inflate(const ChunkHeader& h, const std::string& where, Decompressor& z, std::vector<std::uint8_t>& buffer,
                     std::uint64_t prefix) {
  ChunkRecords out{h.records, static_cast<std::size_t>(h.records_size)};
  if (!h.compression.empty() || h.uncompressed_size != h.records_size) {  // (a size that differs: refused below)
    z.decompress(h.compression, h.records, static_cast<std::size_t>(h.records_size), h.uncompressed_size,
                 where + ": at byte " + std::to_string(h.records_at), buffer, prefix);
    out = {buffer.data(), buffer.size()};
  }
  if (prefix < h.uncompressed_size) {  // (the decompression gave at least `prefix` bytes)
    out.size = static_cast<std::size_t>(std::min<std::uint64_t>(out.size, prefix));
    return out;
  }
  if (h.crc != 0 && crc32Update(0, out.data, out.size) != h.crc)
    throw std::runtime_error(where + ": at byte " + std::to_string(h.records_at) +
                             ": the chunk's records do not match their CRC (damaged data)");
  return out;
}

ChunkIndex parseChunkIndex(ByteCursor& c) {
  ChunkIndex i;
  i.message_start_time = c.u64("ChunkIndex message_start_time");
  i.message_end_time = c.u64("ChunkIndex message_end_time");
  i.chunk_start_offset = c.u64("ChunkIndex chunk_start_offset");
  i.chunk_length = c.u64("ChunkIndex chunk_length");
  const std::uint32_t n = c.u32("ChunkIndex message_index_offsets");
  const std::uint64_t at = c.fileOffset();
  ByteCursor offsets(c.bytes(n, "ChunkIndex message_index_offsets"), n, "", at);
  while (!offsets.done()) {
    const std::uint16_t channel = offsets.u16("ChunkIndex message_index_offsets");
    i.message_index_offsets[channel] = offsets.u64("ChunkIndex message_index_offsets");
  }
  i.message_index_length = c.u64("ChunkIndex message_index_length");
  i.compression = c.string("ChunkIndex compression");
  i.compressed_size = c.u64("ChunkIndex compressed_size");
  i.uncompressed_size = c.u64("ChunkIndex uncompressed_size");
  return i;
}

}  // namespace bimloc::sim::ros2::mcap
