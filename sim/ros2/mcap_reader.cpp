#include "sim/ros2/mcap_reader.hpp"

#include "sim/ros2/byte_cursor.hpp"
#include "sim/ros2/chunk_prefetcher.hpp"
#include "sim/ros2/mcap_records.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>

namespace bimloc::sim::ros2 {

using mcap::ChunkHeader, mcap::inflate, mcap::parseChannel, mcap::parseChunk, mcap::parseChunkIndex, mcap::parseSchema,
    mcap::walkRecords;

bool isMcapFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::uint8_t magic[8] = {};
  return in.read(reinterpret_cast<char*>(magic), 8) && std::memcmp(magic, mcap::kMagic, 8) == 0;
}

struct McapReader::KeptChunk {
  std::size_t index = 0;           // in the read's list of chunks
  std::uint64_t offset = 0;        // the Chunk record's, in the file
  std::set<std::uint16_t> wanted;  // the channels whose messages `chunk` holds
  LoadedChunk chunk;
};

McapReader::~McapReader() = default;

McapReader::McapReader(const std::string& path) : path_(path), file_(path), prefetch_chunks_(defaultPrefetchChunks()) {
  const std::uint8_t* d = file_.data();
  if (file_.size() < 8 || std::memcmp(d, mcap::kMagic, 8) != 0) throw std::runtime_error(path + ": not an MCAP file (no MCAP magic at its start)");
  // Two workers when prefetching: while the reader decodes clouds one keeps up with it; in the
  // small topics' pass, where the reader has little to do, two decompress twice as fast.
  prefetch_workers_ = std::min<std::size_t>(2, prefetch_chunks_);
  buffers_ = std::make_unique<BufferPool>(prefetch_chunks_ + 2);
  data_end_ = file_.size();
  indexed_ = readSummary();
  if (!indexed_) scanData();
}

void McapReader::setPrefetch(std::size_t chunks, std::size_t workers) {
  prefetch_chunks_ = chunks, prefetch_workers_ = workers;
  buffers_->setMost(chunks + 2);
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
      const mcap::ChunkRecords records = inflate(h, path_, decompressor_, buffer);
      const std::string where = path_ + ": chunk at byte " + std::to_string(at) + ", record offset";
      const auto inner_cut = walkRecords(records.data, records.size, 0, where, [&](std::uint8_t iop, ByteCursor& ic, std::uint64_t) {
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

std::size_t McapReader::chunkMessages(std::uint64_t at, const std::set<std::uint16_t>& wanted, Decompressor& z,
                                      LoadedChunk& chunk, std::uint64_t prefix) const {
  const std::uint8_t* d = file_.data();
  if (at + mcap::kRecordHeaderBytes > data_end_ || d[at] != mcap::kChunk)
    throw std::runtime_error(path_ + ": at byte " + std::to_string(at) + ": a chunk index points at something that is not a Chunk record");
  std::uint64_t length;
  std::memcpy(&length, d + at + 1, 8);
  if (length > data_end_ - at - mcap::kRecordHeaderBytes)
    throw std::runtime_error(path_ + ": at byte " + std::to_string(at) + ": a Chunk of " + std::to_string(length) +
                             " bytes runs past the data section");
  ByteCursor c(d + at + mcap::kRecordHeaderBytes, static_cast<std::size_t>(length), path_, at + mcap::kRecordHeaderBytes);
  chunk_loads_.fetch_add(1, std::memory_order_relaxed);
  const ChunkHeader h = parseChunk(c);
  if (!h.compression.empty()) decompressions_.fetch_add(1, std::memory_order_relaxed);
  const mcap::ChunkRecords records = inflate(h, path_, z, chunk.buffer, prefix);
  const std::string where = path_ + ": chunk at byte " + std::to_string(at) + ", record offset";
  std::vector<McapMessage>& out = chunk.messages;
  out.clear();
  const auto cut = walkRecords(records.data, records.size, 0, where, [&](std::uint8_t op, ByteCursor& m, std::uint64_t) {
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
  return out.size();
}

std::vector<std::pair<std::uint64_t, std::uint64_t>> McapReader::messageIndexEntries(std::uint64_t offset, std::uint16_t channel) const {
  const std::uint8_t* d = file_.data();
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
  std::vector<std::pair<std::uint64_t, std::uint64_t>> out;
  while (!entries.done()) {
    const std::uint64_t time = entries.u64("MessageIndex log_time");
    out.emplace_back(time, entries.u64("MessageIndex offset"));
  }
  return out;
}

std::uint64_t McapReader::wantedPrefix(const mcap::ChunkIndex& ci, const std::set<std::uint16_t>& wanted, std::size_t& count) const {
  constexpr std::uint64_t kWhole = UINT64_MAX;
  count = 0;
  if (wanted.empty() || ci.message_index_offsets.empty()) return kWhole;
  std::uint64_t last = 0;
  std::vector<std::uint64_t> others;
  try {
    for (const auto& [channel, offset] : ci.message_index_offsets) {
      const bool is_wanted = wanted.count(channel) > 0;
      for (const auto& [time, at] : messageIndexEntries(offset, channel)) {
        if (is_wanted) last = std::max(last, at), ++count;
        else others.push_back(at);
      }
    }
  } catch (const std::runtime_error&) {  // damaged indexes: the whole chunk, as a whole read finds it
    return kWhole;
  }
  if (count == 0) return kWhole;
  std::uint64_t end = kWhole;
  for (const std::uint64_t at : others)
    if (at > last) end = std::min(end, at);
  return end;
}

std::optional<std::vector<std::uint64_t>> McapReader::indexedLogTimes(const std::set<std::uint16_t>& channel_ids) const {
  if (!indexed_) return std::nullopt;
  std::vector<std::uint64_t> times;
  for (const auto& ci : chunk_indexes_) {
    if (ci.message_index_offsets.empty()) return std::nullopt;  // no message indexes: read the chunks
    for (const auto& [channel, offset] : ci.message_index_offsets)
      if (channel_ids.count(channel))
        for (const auto& [time, at] : messageIndexEntries(offset, channel)) times.push_back(time);
  }
  std::stable_sort(times.begin(), times.end());
  return times;
}

void McapReader::forEachMessage(const std::set<std::uint16_t>& wanted, const std::function<void(const McapMessage&)>& visit,
                                ReadPlan plan) const {
  const std::uint8_t* d = file_.data();
  // The chunks to read, in the order the read reaches them: the prefetcher loads them ahead in
  // that order (on worker threads unless prefetch_chunks_ is 0).
  std::vector<std::uint64_t> chunks, starts;  // file offsets; indexed: their first message's log time
  std::vector<const mcap::ChunkIndex*> indexes;
  if (indexed_) {
    for (const mcap::ChunkIndex& ci : chunk_indexes_) {
      bool has_wanted = wanted.empty() || ci.message_index_offsets.empty();
      for (const auto& [channel, offset] : ci.message_index_offsets) has_wanted = has_wanted || wanted.count(channel);
      if (has_wanted) chunks.push_back(ci.chunk_start_offset), starts.push_back(ci.message_start_time), indexes.push_back(&ci);
      // (else the message indexes say no message of these channels is there)
    }
  } else {
    walkRecords(d + 8, data_end_ - 8, 8, path_, [&](std::uint8_t op, ByteCursor&, std::uint64_t at) {
      if (op == mcap::kDataEnd || op == mcap::kFooter) return false;
      if (op == mcap::kChunk) chunks.push_back(at);
      return true;
    });
  }
  // The chunk an earlier kFirst read of these channels stopped in, when this read starts there.
  std::unique_ptr<KeptChunk> kept;
  {
    std::lock_guard<std::mutex> lock(kept_mutex_);
    kept = std::move(kept_);
  }
  if (kept && (plan != ReadPlan::kAll || kept->index >= chunks.size() || kept->offset != chunks[kept->index] || kept->wanted != wanted))
    kept.reset();
  const bool prefixes = plan == ReadPlan::kSmallTopics && indexed_ && !wanted.empty();
  ChunkPrefetcher prefetcher(chunks.size(), plan == ReadPlan::kFirst ? 0 : prefetch_chunks_, [&](std::size_t i, Decompressor& z, LoadedChunk& chunk) {
    if (kept && i == kept->index) {  // (the one load that touches `kept->chunk`; the reading thread never does)
      buffers_->give(std::move(chunk.buffer));
      chunk = std::move(kept->chunk);
      return;
    }
    if (prefixes) {
      std::size_t count = 0;
      const std::uint64_t prefix = wantedPrefix(*indexes[i], wanted, count);
      if (prefix != UINT64_MAX) {
        try {
          if (chunkMessages(chunks[i], wanted, z, chunk, prefix) == count) return;
        } catch (const std::runtime_error&) {  // damaged within the prefix: the whole read says how
        }
      }  // (and a prefix whose messages do not match the indexes: read whole)
    }
    chunkMessages(chunks[i], wanted, z, chunk);
  }, prefetch_workers_, buffers_.get());
  // A kFirst read that stops (its visit throws) in a chunk, the only one it holds, keeps it.
  std::size_t taken = 0;
  const auto keep = [&](LoadedChunk& chunk, std::size_t index) {
    if (plan != ReadPlan::kFirst) return;
    auto k = std::make_unique<KeptChunk>();
    k->index = index, k->offset = chunks[index], k->wanted = wanted, k->chunk = std::move(chunk);
    std::lock_guard<std::mutex> lock(kept_mutex_);
    kept_ = std::move(k);
  };
  if (indexed_) {
    // Merged by log time over the chunks (sorted by their first message's time): a chunk is read
    // when the merge reaches its first message and released after its last, so that chunks
    // overlapping in time (a topic written in chunks of its own, spanning the whole recording)
    // are merged while only the chunks overlapping the time being read are in memory. Ties go
    // to the earlier chunk, then to the chunk's own order: a stable sort by log time.
    struct Live {
      LoadedChunk chunk;
      std::size_t index = 0;  // in `chunks`
      std::size_t next = 0;
      std::uint64_t time() const { return chunk.messages[next].log_time_ns; }
    };
    std::vector<Live> live;  // in chunk order
    while (true) {
      int first = -1;
      for (int l = 0; l < static_cast<int>(live.size()); ++l)
        if (first < 0 || live[l].time() < live[first].time()) first = l;
      if (taken < chunks.size() && (first < 0 || starts[taken] <= live[first].time())) {
        Live chunk{prefetcher.next(), taken++};
        if (chunk.chunk.messages.empty()) prefetcher.recycle(std::move(chunk.chunk.buffer));
        else live.push_back(std::move(chunk));  // (a moved vector keeps its bytes where they are)
        continue;
      }
      if (first < 0) break;
      Live& chunk = live[static_cast<std::size_t>(first)];
      try {
        visit(chunk.chunk.messages[chunk.next++]);
      } catch (...) {
        if (live.size() == 1) keep(chunk.chunk, chunk.index);
        throw;
      }
      if (chunk.next == chunk.chunk.messages.size()) {
        prefetcher.recycle(std::move(chunk.chunk.buffer));
        live.erase(live.begin() + first);
      }
    }
    return;
  }
  walkRecords(d + 8, data_end_ - 8, 8, path_, [&](std::uint8_t op, ByteCursor& c, std::uint64_t) {
    if (op == mcap::kDataEnd || op == mcap::kFooter) return false;
    if (op == mcap::kChunk) {
      LoadedChunk chunk = prefetcher.next();
      const std::size_t index = taken++;
      try {
        for (const McapMessage& m : chunk.messages) visit(m);
      } catch (...) {
        keep(chunk, index);
        throw;
      }
      prefetcher.recycle(std::move(chunk.buffer));
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
