// The ROS 1 bag format 2.0 (wiki.ros.org/Bags/Format/2.0): after "#ROSBAG V2.0\n", records of
// <header_len u32><header: fields <len u32>name=value><data_len u32><data>. The file header
// (op 3) gives index_pos, conn_count and chunk_count; at index_pos come the connection records
// (op 7) and the chunk info records (op 6, chunk_pos); each chunk (op 5: compression, size) is
// followed by one index record (op 4: ver, conn, count; count x (sec, nsec, offset)) per
// connection it holds.
#include "sim/dataset/ros1_bag_check.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <stdexcept>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace bimloc::sim {
namespace {

constexpr std::uint8_t kOpMessage = 0x02, kOpFileHeader = 0x03, kOpIndex = 0x04, kOpChunk = 0x05, kOpChunkInfo = 0x06,
                       kOpConnection = 0x07;

struct Record {
  std::uint64_t at = 0;  // where the record starts in the file (or the chunk)
  std::map<std::string, std::string> fields;
  std::uint64_t data_at = 0;
  std::uint32_t data_len = 0;
  std::uint64_t end() const { return data_at + data_len; }
  std::optional<std::uint64_t> number(const std::string& name) const {
    const auto it = fields.find(name);
    if (it == fields.end() || it->second.empty() || it->second.size() > 8) return std::nullopt;
    std::uint64_t v = 0;
    std::memcpy(&v, it->second.data(), it->second.size());  // little-endian, as the format
    return v;
  }
  std::optional<std::uint8_t> op() const {
    const auto it = fields.find("op");
    if (it == fields.end() || it->second.size() != 1) return std::nullopt;
    return static_cast<std::uint8_t>(it->second[0]);
  }
};

// Read with pread, exactly the bytes wanted: a buffered stream refills 8 KiB at every seek, and
// the walk seeks at every record (126 MB of reads for a 127 MB bag of 20 s).
class BagFile {
 public:
  explicit BagFile(const std::string& path) : path_(path), fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {
    struct stat st {};
    size_ = fd_ >= 0 && ::fstat(fd_, &st) == 0 ? static_cast<std::uint64_t>(st.st_size) : 0;
  }
  ~BagFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  BagFile(const BagFile&) = delete;
  BagFile& operator=(const BagFile&) = delete;
  std::uint64_t size() const { return size_; }

  // The record at `at` whose bytes must end by `limit`; nullopt where it does not parse.
  std::optional<Record> record(std::uint64_t at, std::uint64_t limit) {
    Record r;
    r.at = at;
    if (limit < 8 || at > limit - 8) return std::nullopt;
    // Most records' header and data length fit in the first 512 bytes: one read.
    std::string head(static_cast<std::size_t>(std::min<std::uint64_t>(512, limit - at)), '\0');
    if (!bytes(at, head.data(), head.size())) return std::nullopt;
    std::uint32_t header_len = 0;
    std::memcpy(&header_len, head.data(), 4);
    if (header_len > limit - at - 8) return std::nullopt;
    if (head.size() < std::size_t{header_len} + 8) {
      head.resize(std::size_t{header_len} + 8);
      if (!bytes(at, head.data(), head.size())) return std::nullopt;
    }
    const std::string header = head.substr(4, header_len);
    for (std::size_t p = 0; p < header.size();) {
      std::uint32_t len = 0;
      if (header.size() - p < 4) return std::nullopt;
      std::memcpy(&len, header.data() + p, 4);
      p += 4;
      if (len > header.size() - p) return std::nullopt;
      const std::string field = header.substr(p, len);
      p += len;
      const std::size_t eq = field.find('=');
      if (eq == std::string::npos) return std::nullopt;
      r.fields[field.substr(0, eq)] = field.substr(eq + 1);
    }
    std::memcpy(&r.data_len, head.data() + 4 + header_len, 4);
    r.data_at = at + 4 + header_len + 4;
    if (r.data_len > limit - r.data_at) return std::nullopt;
    return r;
  }
  bool bytes(std::uint64_t at, char* out, std::size_t n) {
    while (n > 0) {
      const ssize_t got = ::pread(fd_, out, n, static_cast<off_t>(at));
      if (got <= 0) return false;
      out += got, at += static_cast<std::uint64_t>(got), n -= static_cast<std::size_t>(got);
    }
    return true;
  }
  [[noreturn]] void fail(std::uint64_t at, const std::string& what) const {
    throw std::runtime_error(path_ + ": at byte " + std::to_string(at) + ": " + what);
  }

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

// The message records of an uncompressed chunk (offsets from its data's start): each must end
// within the chunk, as rosbag reads them from its buffer unchecked.
std::vector<std::uint32_t> messageOffsets(BagFile& file, const Record& chunk) {
  std::vector<std::uint32_t> offsets;
  for (std::uint64_t at = chunk.data_at; at < chunk.end();) {
    const auto r = file.record(at, chunk.end());
    if (!r) file.fail(at, "a record of the uncompressed chunk at byte " + std::to_string(chunk.at) + " runs past the chunk's end");
    if (r->op() == kOpMessage) offsets.push_back(static_cast<std::uint32_t>(at - chunk.data_at));
    at = r->end();
  }
  return offsets;
}

void checkChunk(BagFile& file, std::uint64_t chunk_pos, std::size_t connections, const std::map<std::uint32_t, std::string>& topics,
                std::vector<Ros1ChunkEnd>& ends) {
  const std::string name = "the chunk at byte " + std::to_string(chunk_pos);
  const auto chunk = file.record(chunk_pos, file.size());
  if (!chunk || chunk->op() != kOpChunk) file.fail(chunk_pos, name + " (from the index): no chunk record there, or it runs past the file's end");
  const auto compression = chunk->fields.find("compression");
  const auto size = chunk->number("size");
  if (compression == chunk->fields.end() || !size) file.fail(chunk_pos, name + ": no compression or size field");
  const std::string& how = compression->second;
  if (how != "none" && how != "lz4" && how != "bz2")
    file.fail(chunk_pos, name + ": compression '" + how + "' unknown (a ROS 1 bag's chunks are none, lz4 or bz2)");
  if (how == "none" && *size != chunk->data_len)
    file.fail(chunk_pos, name + ": uncompressed, yet its size field says " + std::to_string(*size) + " bytes and it holds " +
                             std::to_string(chunk->data_len));
  const std::vector<std::uint32_t> messages = how == "none" ? messageOffsets(file, *chunk) : std::vector<std::uint32_t>{};
  std::uint64_t at = chunk->end();
  Ros1ChunkEnd end;
  end.chunk_pos = chunk_pos, end.size = static_cast<std::uint32_t>(*size);
  bool any = false;
  for (std::size_t c = 0; c < connections; ++c) {
    const auto index = file.record(at, file.size());
    if (!index || index->op() != kOpIndex) return;  // rosbag says what is wrong with it
    const auto count = index->number("count");
    if (!count || *count * 12 != index->data_len)
      file.fail(at, "the index of " + name + ": its count says " + std::to_string(count.value_or(0)) + " entries, its " +
                        std::to_string(index->data_len) + " bytes hold " + std::to_string(index->data_len / 12.0));
    const auto topic = topics.find(static_cast<std::uint32_t>(index->number("conn").value_or(~0u)));
    std::vector<std::uint32_t> entries(static_cast<std::size_t>(*count) * 3);  // (sec, nsec, offset) each
    if (!file.bytes(index->data_at, reinterpret_cast<char*>(entries.data()), index->data_len)) return;
    for (std::uint64_t e = 0; e < *count; ++e) {
      const std::uint32_t sec = entries[3 * e], nsec = entries[3 * e + 1], offset = entries[3 * e + 2];
      if (topic != topics.end() && (!any || offset > end.last_offset)) {
        any = true;
        end.last_offset = offset, end.topic = topic->second;
        end.stamp_ns = std::uint64_t{sec} * 1000000000u + nsec;
      }
      // The smallest record: header and data lengths, and the "op" field.
      const bool inside = std::uint64_t{offset} + 4 + 8 + 4 <= *size;
      const bool message = how != "none" || std::binary_search(messages.begin(), messages.end(), offset);
      if (!inside || !message)
        file.fail(index->data_at + 12 * e + 8, "the index of " + name + ": entry " + std::to_string(e) + " points at byte " +
                                                    std::to_string(offset) + " of the chunk's " + std::to_string(*size) +
                                                    (inside ? ", where no message record starts" : ", past its end"));
    }
    at = index->end();
  }
  if (any && how != "none") ends.push_back(end);
}

}  // namespace

std::vector<Ros1ChunkEnd> checkRos1BagRecords(const std::string& path) {
  std::vector<Ros1ChunkEnd> ends;
  BagFile file(path);
  const std::uint64_t first = 13;  // "#ROSBAG V2.0\n"
  const auto header = file.record(first, file.size());
  if (!header || header->op() != kOpFileHeader || header->fields.count("encryptor")) return ends;  // rosbag's to say
  const auto index_pos = header->number("index_pos");
  const auto connections = header->number("conn_count"), chunks = header->number("chunk_count");
  if (!index_pos || *index_pos == 0 || !connections || !chunks) return ends;  // unindexed: rosbag says so
  if (*index_pos >= file.size()) file.fail(first, "the file header's index_pos " + std::to_string(*index_pos) + " lies past the file's end (" + std::to_string(file.size()) + " bytes)");
  std::uint64_t at = *index_pos;
  std::map<std::uint32_t, std::string> topics;
  for (std::uint64_t c = 0; c < *connections; ++c) {
    const auto r = file.record(at, file.size());
    if (!r || r->op() != kOpConnection) return ends;
    if (const auto id = r->number("conn"); id && r->fields.count("topic")) topics[static_cast<std::uint32_t>(*id)] = r->fields.at("topic");
    at = r->end();
  }
  for (std::uint64_t c = 0; c < *chunks; ++c) {
    const auto info = file.record(at, file.size());
    if (!info || info->op() != kOpChunkInfo) return ends;
    const auto chunk_pos = info->number("chunk_pos");
    const auto count = info->number("count");
    if (!chunk_pos || !count || *count * 8 != info->data_len)
      file.fail(at, "a chunk info record: its count says " + std::to_string(count.value_or(0)) + " connections, its " +
                        std::to_string(info->data_len) + " bytes hold " + std::to_string(info->data_len / 8.0));
    checkChunk(file, *chunk_pos, static_cast<std::size_t>(*count), topics, ends);
    at = info->end();
  }
  return ends;
}

}  // namespace bimloc::sim
