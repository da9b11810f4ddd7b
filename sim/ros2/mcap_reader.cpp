#include "sim/ros2/mcap_reader.hpp"

#include "sim/ros2/byte_cursor.hpp"
#include "sim/ros2/compression.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>

namespace bimloc::sim::ros2 {
namespace {

using RecordVisitor = std::function<bool(std::uint8_t opcode, ByteCursor& content, std::uint64_t at)>;

// Walks the records of data[0, size) (`base`: the offset of data[0] in the file, or in the
// chunk). Returns where a record is cut short (the data ends inside it), or nothing when every
// record is whole. `visit` returns false to stop.
std::optional<std::uint64_t> walkRecords(const std::uint8_t* data, std::size_t size, std::uint64_t base,
                                         const std::string& where, const RecordVisitor& visit) {
  std::size_t pos = 0;
  while (pos < size) {
    if (size - pos < mcap::kRecordHeaderBytes) return base + pos;
    const std::uint8_t opcode = data[pos];
    std::uint64_t length;
    std::memcpy(&length, data + pos + 1, 8);
    if (length > size - pos - mcap::kRecordHeaderBytes) return base + pos;
    ByteCursor content(data + pos + mcap::kRecordHeaderBytes, static_cast<std::size_t>(length), where,
                       base + pos + mcap::kRecordHeaderBytes);
    if (!visit(opcode, content, base + pos)) return std::nullopt;
    pos += mcap::kRecordHeaderBytes + static_cast<std::size_t>(length);
  }
  return std::nullopt;
}

mcap::Schema parseSchema(ByteCursor& c) {
  mcap::Schema s;
  s.id = c.u16("Schema id");
  s.name = c.string("Schema name");
  s.encoding = c.string("Schema encoding");
  const std::uint32_t n = c.u32("Schema data");
  s.data.assign(reinterpret_cast<const char*>(c.bytes(n, "Schema data")), n);
  return s;
}

mcap::Channel parseChannel(ByteCursor& c) {
  mcap::Channel ch;
  ch.id = c.u16("Channel id");
  ch.schema_id = c.u16("Channel schema_id");
  ch.topic = c.string("Channel topic");
  ch.message_encoding = c.string("Channel message_encoding");
  ch.metadata = c.stringMap("Channel metadata");
  return ch;
}

struct ChunkHeader {
  std::uint64_t start = 0, end = 0, uncompressed_size = 0;
  std::uint32_t crc = 0;
  std::string compression;
  const std::uint8_t* records = nullptr;
  std::uint64_t records_size = 0, records_at = 0;
};

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

// The chunk's records, decompressed and checked against their CRC (when it is not 0).
void inflate(const ChunkHeader& h, const std::string& where, std::vector<std::uint8_t>& out) {
  out = decompress(h.compression, h.records, static_cast<std::size_t>(h.records_size), h.uncompressed_size,
                   where + ": at byte " + std::to_string(h.records_at));
  if (h.crc != 0 && crc32Update(0, out.data(), out.size()) != h.crc)
    throw std::runtime_error(where + ": at byte " + std::to_string(h.records_at) +
                             ": the chunk's records do not match their CRC (damaged data)");
}

mcap::ChunkIndex parseChunkIndex(ByteCursor& c) {
  mcap::ChunkIndex i;
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

}  // namespace

bool isMcapFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::uint8_t magic[8] = {};
  return in.read(reinterpret_cast<char*>(magic), 8) && std::memcmp(magic, mcap::kMagic, 8) == 0;
}

McapReader::McapReader(const std::string& path) : path_(path), file_(path) {
  const std::uint8_t* d = file_.data();
  if (file_.size() < 8 || std::memcmp(d, mcap::kMagic, 8) != 0) throw std::runtime_error(path + ": not an MCAP file (no MCAP magic at its start)");
  data_end_ = file_.size();
  indexed_ = readSummary();
  if (!indexed_) scanData();
}

const mcap::Schema* McapReader::schemaOf(const mcap::Channel& c) const {
  const auto it = schemas_.find(c.schema_id);
  return it == schemas_.end() ? nullptr : &it->second;
}

bool McapReader::readSummary() {
  const std::uint8_t* d = file_.data();
  const std::size_t size = file_.size();
  const std::size_t trailer = mcap::kFooterBytes + 8;
  if (size < 8 + trailer || std::memcmp(d + size - 8, mcap::kMagic, 8) != 0) {
    warnings_.push_back(path_ + ": no MCAP footer at its end (a recording cut short?): read by a linear scan");
    return false;
  }
  const std::size_t footer_at = size - trailer;
  ByteCursor footer(d + footer_at, mcap::kFooterBytes, path_, footer_at);
  const std::uint8_t opcode = footer.u8("Footer opcode");
  const std::uint64_t length = footer.u64("Footer length");
  if (opcode != mcap::kFooter || length != 20) footer.fail("the record before the closing magic is not a Footer");
  const std::uint64_t summary_start = footer.u64("Footer summary_start");
  const std::uint64_t summary_offset_start = footer.u64("Footer summary_offset_start");
  data_end_ = footer_at;
  if (summary_start == 0) return false;  // a file written without a summary
  if (summary_start < 8 || summary_start > footer_at || summary_offset_start > footer_at ||
      (summary_offset_start != 0 && summary_offset_start < summary_start)) {
    warnings_.push_back(path_ + ": at byte " + std::to_string(footer_at) + ": the Footer's summary offsets lie outside the file: read by a linear scan");
    return false;
  }
  data_end_ = summary_start;
  const std::uint64_t summary_end = summary_offset_start != 0 ? summary_offset_start : footer_at;
  std::map<std::uint16_t, std::uint64_t> stats_counts;
  bool have_stats = false;
  const auto cut = walkRecords(d + summary_start, summary_end - summary_start, summary_start, path_,
                               [&](std::uint8_t op, ByteCursor& c, std::uint64_t) {
                                 if (op == mcap::kSchema) {
                                   mcap::Schema s = parseSchema(c);
                                   schemas_[s.id] = std::move(s);
                                 } else if (op == mcap::kChannel) {
                                   mcap::Channel ch = parseChannel(c);
                                   channels_[ch.id] = std::move(ch);
                                 } else if (op == mcap::kChunkIndex) {
                                   chunk_indexes_.push_back(parseChunkIndex(c));
                                 } else if (op == mcap::kStatistics) {
                                   c.skip(8 + 2 + 4 * 4 + 8 + 8, "Statistics");  // counts, then message_start_time, message_end_time
                                   const std::uint32_t n = c.u32("Statistics channel_message_counts");
                                   const std::uint64_t at = c.fileOffset();
                                   ByteCursor m(c.bytes(n, "Statistics channel_message_counts"), n, path_, at);
                                   while (!m.done()) {
                                     const std::uint16_t ch = m.u16("Statistics channel_message_counts");
                                     stats_counts[ch] = m.u64("Statistics channel_message_counts");
                                   }
                                   have_stats = true;
                                 }
                                 return true;
                               });
  if (cut) throw std::runtime_error(path_ + ": at byte " + std::to_string(*cut) + ": a summary record runs past the summary section");
  for (const auto& [id, ch] : channels_)
    if (ch.schema_id != 0 && !schemas_.count(ch.schema_id))
      throw std::runtime_error(path_ + ": channel " + std::to_string(id) + " (" + ch.topic + ") refers to schema " +
                               std::to_string(ch.schema_id) + ", which the summary does not have");
  for (const auto& ci : chunk_indexes_)
    if (ci.chunk_start_offset < 8 || ci.chunk_start_offset > data_end_ || ci.chunk_length > data_end_ - ci.chunk_start_offset)
      throw std::runtime_error(path_ + ": a chunk index points at bytes " + std::to_string(ci.chunk_start_offset) + " + " +
                               std::to_string(ci.chunk_length) + ", outside the data section (" + std::to_string(data_end_) + " bytes)");
  if (chunk_indexes_.empty()) {  // a summary without chunk indexes: the messages need a scan
    schemas_.clear(), channels_.clear();
    return false;
  }
  if (have_stats) {
    counts_ = stats_counts;
  } else {  // count from the message indexes: 16 bytes per message
    for (const auto& ci : chunk_indexes_)
      for (const auto& [channel, offset] : ci.message_index_offsets) {
        if (offset < 8 || offset > data_end_ || data_end_ - offset < mcap::kRecordHeaderBytes + 6 || d[offset] != mcap::kMessageIndex)
          throw std::runtime_error(path_ + ": at byte " + std::to_string(offset) + ": a chunk index points at no MessageIndex record");
        std::uint32_t n;
        std::memcpy(&n, d + offset + mcap::kRecordHeaderBytes + 2, 4);
        counts_[channel] += n / 16;  // (log_time, offset) pairs
      }
  }
  for (const auto& [id, ch] : channels_) counts_.emplace(id, 0);
  std::stable_sort(chunk_indexes_.begin(), chunk_indexes_.end(),
                   [](const auto& a, const auto& b) { return a.message_start_time < b.message_start_time; });
  return true;
}

void McapReader::scanData() {
  const std::uint8_t* d = file_.data();
  std::vector<std::uint8_t> buffer;
  auto addRecord = [&](std::uint8_t op, ByteCursor& c, const std::string& where) {
    if (op == mcap::kSchema) {
      mcap::Schema s = parseSchema(c);
      schemas_[s.id] = std::move(s);
    } else if (op == mcap::kChannel) {
      mcap::Channel ch = parseChannel(c);
      if (ch.schema_id != 0 && !schemas_.count(ch.schema_id))
        c.fail("channel " + std::to_string(ch.id) + " (" + ch.topic + ") refers to schema " + std::to_string(ch.schema_id) +
               ", not defined before it");
      counts_.emplace(ch.id, 0);
      channels_[ch.id] = std::move(ch);
    } else if (op == mcap::kMessage) {
      const std::uint16_t channel = c.u16("Message channel_id");
      if (!channels_.count(channel)) c.fail("a message on channel " + std::to_string(channel) + ", not defined before it");
      ++counts_[channel];
    }
    (void)where;
  };
  std::optional<std::uint64_t> cut = walkRecords(d + 8, data_end_ - 8, 8, path_, [&](std::uint8_t op, ByteCursor& c, std::uint64_t at) {
    if (op == mcap::kDataEnd || op == mcap::kFooter) return false;
    if (op == mcap::kChunk) {
      ChunkHeader h = parseChunk(c);
      inflate(h, path_, buffer);
      const std::string where = path_ + ": chunk at byte " + std::to_string(at) + ", record offset";
      const auto inner_cut = walkRecords(buffer.data(), buffer.size(), 0, where, [&](std::uint8_t iop, ByteCursor& ic, std::uint64_t) {
        addRecord(iop, ic, where);
        return true;
      });
      if (inner_cut) throw std::runtime_error(where + " " + std::to_string(*inner_cut) + ": a record runs past the chunk's end");
    } else {
      addRecord(op, c, path_);
    }
    return true;
  });
  if (cut) {
    std::uint64_t messages = 0;
    for (const auto& [id, n] : counts_) messages += n;
    warnings_.push_back(path_ + ": cut short at byte " + std::to_string(*cut) + " of " + std::to_string(file_.size()) +
                        " (a recording that did not finish): read the " + std::to_string(messages) + " whole messages before it");
    data_end_ = *cut;
  }
}

std::vector<McapMessage> McapReader::chunkMessages(std::uint64_t at, const std::set<std::uint16_t>& wanted,
                                                   std::vector<std::uint8_t>& buffer) const {
  const std::uint8_t* d = file_.data();
  if (at + mcap::kRecordHeaderBytes > data_end_ || d[at] != mcap::kChunk)
    throw std::runtime_error(path_ + ": at byte " + std::to_string(at) + ": a chunk index points at something that is not a Chunk record");
  std::uint64_t length;
  std::memcpy(&length, d + at + 1, 8);
  if (length > data_end_ - at - mcap::kRecordHeaderBytes)
    throw std::runtime_error(path_ + ": at byte " + std::to_string(at) + ": a Chunk of " + std::to_string(length) +
                             " bytes runs past the data section");
  ByteCursor c(d + at + mcap::kRecordHeaderBytes, static_cast<std::size_t>(length), path_, at + mcap::kRecordHeaderBytes);
  const ChunkHeader h = parseChunk(c);
  inflate(h, path_, buffer);
  const std::string where = path_ + ": chunk at byte " + std::to_string(at) + ", record offset";
  std::vector<McapMessage> out;
  const auto cut = walkRecords(buffer.data(), buffer.size(), 0, where, [&](std::uint8_t op, ByteCursor& m, std::uint64_t) {
    if (op != mcap::kMessage) return true;
    McapMessage msg;
    const std::uint16_t channel = m.u16("Message channel_id");
    if (!wanted.empty() && !wanted.count(channel)) return true;
    const auto ch = channels_.find(channel);
    if (ch == channels_.end()) m.fail("a message on channel " + std::to_string(channel) + ", which the file does not define");
    msg.channel = &ch->second;
    msg.sequence = m.u32("Message sequence");
    msg.log_time_ns = m.u64("Message log_time");
    msg.publish_time_ns = m.u64("Message publish_time");
    msg.size = m.remaining();
    msg.data = m.bytes(msg.size, "Message data");
    out.push_back(msg);
    return true;
  });
  if (cut) throw std::runtime_error(where + " " + std::to_string(*cut) + ": a record runs past the chunk's end");
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.log_time_ns < b.log_time_ns; });
  return out;
}

std::optional<std::vector<std::uint64_t>> McapReader::indexedLogTimes(const std::set<std::uint16_t>& channel_ids) const {
  if (!indexed_) return std::nullopt;
  const std::uint8_t* d = file_.data();
  std::vector<std::uint64_t> times;
  for (const auto& ci : chunk_indexes_) {
    if (ci.message_index_offsets.empty()) return std::nullopt;  // no message indexes: read the chunks
    for (const auto& [channel, offset] : ci.message_index_offsets) {
      if (!channel_ids.count(channel)) continue;
      if (offset < 8 || offset > data_end_ || data_end_ - offset < mcap::kRecordHeaderBytes || d[offset] != mcap::kMessageIndex)
        throw std::runtime_error(path_ + ": at byte " + std::to_string(offset) + ": a chunk index points at no MessageIndex record");
      std::uint64_t length;
      std::memcpy(&length, d + offset + 1, 8);
      if (length > data_end_ - offset - mcap::kRecordHeaderBytes)
        throw std::runtime_error(path_ + ": at byte " + std::to_string(offset) + ": a MessageIndex runs past the data section");
      ByteCursor c(d + offset + mcap::kRecordHeaderBytes, static_cast<std::size_t>(length), path_, offset + mcap::kRecordHeaderBytes);
      if (c.u16("MessageIndex channel_id") != channel) c.fail("a MessageIndex of another channel than its chunk index says");
      const std::uint32_t n = c.u32("MessageIndex records");
      ByteCursor entries(c.bytes(n, "MessageIndex records"), n, path_, c.fileOffset());
      while (!entries.done()) {
        times.push_back(entries.u64("MessageIndex log_time"));
        entries.u64("MessageIndex offset");
      }
    }
  }
  std::stable_sort(times.begin(), times.end());
  return times;
}

void McapReader::forEachMessage(const std::set<std::uint16_t>& wanted, const std::function<void(const McapMessage&)>& visit) const {
  const std::uint8_t* d = file_.data();
  if (indexed_) {
    // Chunks whose times overlap are read together and their messages merged by log time.
    std::size_t i = 0;
    while (i < chunk_indexes_.size()) {
      std::size_t j = i + 1;
      std::uint64_t end = chunk_indexes_[i].message_end_time;
      while (j < chunk_indexes_.size() && chunk_indexes_[j].message_start_time < end)
        end = std::max(end, chunk_indexes_[j++].message_end_time);
      std::vector<std::vector<std::uint8_t>> buffers(j - i);
      std::vector<McapMessage> merged;
      for (std::size_t k = i; k < j; ++k) {
        const mcap::ChunkIndex& ci = chunk_indexes_[k];
        bool has_wanted = wanted.empty() || ci.message_index_offsets.empty();
        for (const auto& [channel, offset] : ci.message_index_offsets) has_wanted = has_wanted || wanted.count(channel);
        if (!has_wanted) continue;  // the message indexes say no message of these channels is here
        std::vector<McapMessage> m = chunkMessages(ci.chunk_start_offset, wanted, buffers[k - i]);
        merged.insert(merged.end(), m.begin(), m.end());
      }
      if (j - i > 1)
        std::stable_sort(merged.begin(), merged.end(), [](const auto& a, const auto& b) { return a.log_time_ns < b.log_time_ns; });
      for (const McapMessage& m : merged) visit(m);
      i = j;
    }
    return;
  }
  std::vector<std::uint8_t> buffer;
  walkRecords(d + 8, data_end_ - 8, 8, path_, [&](std::uint8_t op, ByteCursor& c, std::uint64_t at) {
    if (op == mcap::kDataEnd || op == mcap::kFooter) return false;
    if (op == mcap::kChunk) {
      for (const McapMessage& m : chunkMessages(at, wanted, buffer)) visit(m);
    } else if (op == mcap::kMessage) {
      McapMessage msg;
      const std::uint16_t channel = c.u16("Message channel_id");
      if (!wanted.empty() && !wanted.count(channel)) return true;
      msg.channel = &channels_.at(channel);  // the constructor's scan checked it
      msg.sequence = c.u32("Message sequence");
      msg.log_time_ns = c.u64("Message log_time");
      msg.publish_time_ns = c.u64("Message publish_time");
      msg.size = c.remaining();
      msg.data = c.bytes(msg.size, "Message data");
      visit(msg);
    }
    return true;
  });
}

}  // namespace bimloc::sim::ros2
