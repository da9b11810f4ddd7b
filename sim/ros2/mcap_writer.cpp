#include "sim/ros2/mcap_writer.hpp"

#include "sim/ros2/byte_cursor.hpp"
#include "sim/ros2/compression.hpp"
#include "sim/ros2/crc32.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace bimloc::sim::ros2 {
namespace {

// A record's content, built little endian.
class Bytes {
 public:
  Bytes& u8(std::uint8_t v) { return raw(&v, 1); }
  Bytes& u16(std::uint16_t v) { return raw(&v, 2); }
  Bytes& u32(std::uint32_t v) { return raw(&v, 4); }
  Bytes& u64(std::uint64_t v) { return raw(&v, 8); }
  Bytes& str(const std::string& s) { return u32(static_cast<std::uint32_t>(s.size())).raw(s.data(), s.size()); }
  Bytes& raw(const void* p, std::size_t n) {
    const auto* b = static_cast<const std::uint8_t*>(p);
    data.insert(data.end(), b, b + n);
    return *this;
  }
  Bytes& map(const std::map<std::string, std::string>& m) {
    Bytes inner;
    for (const auto& [k, v] : m) inner.str(k).str(v);
    return u32(static_cast<std::uint32_t>(inner.data.size())).raw(inner.data.data(), inner.data.size());
  }
  std::vector<std::uint8_t> data;
};

std::vector<std::uint8_t> record(std::uint8_t opcode, const Bytes& content) {
  Bytes r;
  r.u8(opcode).u64(content.data.size()).raw(content.data.data(), content.data.size());
  return std::move(r.data);
}

Bytes schemaRecord(const mcap::Schema& s) {
  Bytes b;
  b.u16(s.id).str(s.name).str(s.encoding).u32(static_cast<std::uint32_t>(s.data.size())).raw(s.data.data(), s.data.size());
  return b;
}

Bytes channelRecord(const mcap::Channel& c) {
  Bytes b;
  b.u16(c.id).u16(c.schema_id).str(c.topic).str(c.message_encoding).map(c.metadata);
  return b;
}

}  // namespace

McapWriter::McapWriter(const std::string& path, McapWriterOptions options) : path_(path), options_(std::move(options)) {
  if (options_.compression != "" && options_.compression != "zstd" && options_.compression != "lz4")
    throw std::invalid_argument("MCAP: unknown compression '" + options_.compression + "'");
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw std::runtime_error(path + ": cannot create: " + std::strerror(errno));
  put(std::vector<std::uint8_t>(mcap::kMagic, mcap::kMagic + 8));
  Bytes header;
  header.str(options_.profile).str(options_.library);
  put(record(mcap::kHeader, header));
}

McapWriter::~McapWriter() {
  if (file_) std::fclose(file_);
}

void McapWriter::put(const std::vector<std::uint8_t>& bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
    throw std::runtime_error(path_ + ": cannot write: " + std::strerror(errno));
  offset_ += bytes.size();
}

std::uint16_t McapWriter::addSchema(const std::string& name, const std::string& encoding, const std::string& data) {
  mcap::Schema s;
  s.id = static_cast<std::uint16_t>(schemas_.size() + 1);  // 0 means "no schema"
  s.name = name, s.encoding = encoding, s.data = data;
  put(record(mcap::kSchema, schemaRecord(s)));
  schemas_[s.id] = s;
  return s.id;
}

std::uint16_t McapWriter::addChannel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                                     const std::map<std::string, std::string>& metadata) {
  mcap::Channel c;
  c.id = static_cast<std::uint16_t>(channels_.size());
  c.schema_id = schema_id, c.topic = topic, c.message_encoding = message_encoding, c.metadata = metadata;
  put(record(mcap::kChannel, channelRecord(c)));
  channels_[c.id] = c;
  counts_[c.id] = 0;
  return c.id;
}

void McapWriter::write(std::uint16_t channel_id, std::uint64_t log_time_ns, std::uint64_t publish_time_ns,
                       const std::uint8_t* data, std::size_t size) {
  if (!channels_.count(channel_id)) throw std::invalid_argument("MCAP: no channel " + std::to_string(channel_id));
  if (chunk_index_.empty()) chunk_start_ = chunk_end_ = log_time_ns;
  chunk_start_ = std::min(chunk_start_, log_time_ns);
  chunk_end_ = std::max(chunk_end_, log_time_ns);
  if (messages_ == 0) first_time_ = last_time_ = log_time_ns;
  first_time_ = std::min(first_time_, log_time_ns);
  last_time_ = std::max(last_time_, log_time_ns);
  chunk_index_[channel_id].push_back({log_time_ns, chunk_.size()});
  Bytes m;
  m.u16(channel_id).u32(sequence_[channel_id]++).u64(log_time_ns).u64(publish_time_ns).raw(data, size);
  const auto r = record(mcap::kMessage, m);
  chunk_.insert(chunk_.end(), r.begin(), r.end());
  ++counts_[channel_id], ++messages_;
  if (chunk_.size() >= options_.chunk_bytes) flushChunk();
}

void McapWriter::flushChunk() {
  if (chunk_index_.empty()) return;
  const std::vector<std::uint8_t> compressed = compress(options_.compression, chunk_);
  mcap::ChunkIndex ci;
  ci.message_start_time = chunk_start_, ci.message_end_time = chunk_end_;
  ci.chunk_start_offset = offset_;
  ci.compression = options_.compression;
  ci.compressed_size = compressed.size(), ci.uncompressed_size = chunk_.size();
  Bytes chunk;
  chunk.u64(chunk_start_).u64(chunk_end_).u64(chunk_.size()).u32(crc32Update(0, chunk_.data(), chunk_.size()));
  chunk.str(options_.compression).u64(compressed.size()).raw(compressed.data(), compressed.size());
  put(record(mcap::kChunk, chunk));
  ci.chunk_length = offset_ - ci.chunk_start_offset;
  const std::uint64_t indexes_start = offset_;
  for (const auto& [channel, entries] : chunk_index_) {
    ci.message_index_offsets[channel] = offset_;
    Bytes index;
    index.u16(channel).u32(static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [time, at] : entries) index.u64(time).u64(at);
    put(record(mcap::kMessageIndex, index));
  }
  ci.message_index_length = offset_ - indexes_start;
  chunk_indexes_.push_back(std::move(ci));
  chunk_.clear();
  chunk_index_.clear();
}

void McapWriter::close() {
  if (!file_) return;
  flushChunk();
  Bytes data_end;
  data_end.u32(0);  // no data section CRC
  put(record(mcap::kDataEnd, data_end));
  std::uint64_t summary_start = 0, summary_offset_start = 0;
  std::vector<std::uint8_t> tail;  // the summary, its offsets, and the footer's first fields: the summary CRC covers them
  if (options_.summary) {
    summary_start = offset_;
    struct Group {
      std::uint8_t opcode;
      std::uint64_t start, length;
    };
    std::vector<Group> groups;
    auto group = [&](std::uint8_t opcode, const std::vector<Bytes>& contents) {
      if (contents.empty()) return;
      const std::uint64_t start = summary_start + tail.size();
      for (const Bytes& c : contents) {
        const auto r = record(opcode, c);
        tail.insert(tail.end(), r.begin(), r.end());
      }
      groups.push_back({opcode, start, summary_start + tail.size() - start});
    };
    std::vector<Bytes> schemas, channels, chunk_indexes;
    for (const auto& [id, s] : schemas_) schemas.push_back(schemaRecord(s));
    for (const auto& [id, c] : channels_) channels.push_back(channelRecord(c));
    Bytes stats;
    stats.u64(messages_).u16(static_cast<std::uint16_t>(schemas_.size())).u32(static_cast<std::uint32_t>(channels_.size()));
    stats.u32(0).u32(0).u32(static_cast<std::uint32_t>(chunk_indexes_.size()));
    stats.u64(messages_ ? first_time_ : 0).u64(messages_ ? last_time_ : 0);
    Bytes counts;
    for (const auto& [id, n] : counts_) counts.u16(id).u64(n);
    stats.u32(static_cast<std::uint32_t>(counts.data.size())).raw(counts.data.data(), counts.data.size());
    for (const auto& ci : chunk_indexes_) {
      Bytes b;
      b.u64(ci.message_start_time).u64(ci.message_end_time).u64(ci.chunk_start_offset).u64(ci.chunk_length);
      Bytes offsets;
      for (const auto& [channel, at] : ci.message_index_offsets) offsets.u16(channel).u64(at);
      b.u32(static_cast<std::uint32_t>(offsets.data.size())).raw(offsets.data.data(), offsets.data.size());
      b.u64(ci.message_index_length).str(ci.compression).u64(ci.compressed_size).u64(ci.uncompressed_size);
      chunk_indexes.push_back(b);
    }
    group(mcap::kSchema, schemas);
    group(mcap::kChannel, channels);
    group(mcap::kStatistics, {stats});
    group(mcap::kChunkIndex, chunk_indexes);
    summary_offset_start = summary_start + tail.size();
    for (const Group& g : groups) {
      Bytes o;
      o.u8(g.opcode).u64(g.start).u64(g.length);
      const auto r = record(mcap::kSummaryOffset, o);
      tail.insert(tail.end(), r.begin(), r.end());
    }
  }
  Bytes footer_head;
  footer_head.u8(mcap::kFooter).u64(20).u64(summary_start).u64(summary_offset_start);
  tail.insert(tail.end(), footer_head.data.begin(), footer_head.data.end());
  const std::uint32_t crc = options_.summary ? crc32Update(0, tail.data(), tail.size()) : 0;
  Bytes end;
  end.u32(crc).raw(mcap::kMagic, 8);
  tail.insert(tail.end(), end.data.begin(), end.data.end());
  put(tail);
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0) throw std::runtime_error(path_ + ": cannot finish: " + std::strerror(errno));
}

std::uint64_t McapWriter::messageCount(std::uint16_t channel_id) const {
  const auto it = counts_.find(channel_id);
  return it == counts_.end() ? 0 : it->second;
}

}  // namespace bimloc::sim::ros2
