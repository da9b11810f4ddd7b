// A little-endian reader over a bounded byte range, for MCAP's records: every length is checked
// against what is left before it is used, and an error names the file, the byte offset in the
// file and the field ("FILE: at byte 1234: Channel topic: needs 70 bytes, 12 left").
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

namespace bimloc::sim::ros2 {

class ByteCursor {
 public:
  // `file_offset`: where `data` lies in the file (or, inside a decompressed chunk, a label
  // given in `where` and the offset within the chunk).
  ByteCursor(const std::uint8_t* data, std::size_t size, std::string where, std::uint64_t file_offset)
      : data_(data), size_(size), where_(std::move(where)), base_(file_offset) {}

  std::size_t remaining() const { return size_ - pos_; }
  std::size_t position() const { return pos_; }
  std::uint64_t fileOffset() const { return base_ + pos_; }
  bool done() const { return pos_ == size_; }

  std::uint8_t u8(const char* field);
  std::uint16_t u16(const char* field);
  std::uint32_t u32(const char* field);
  std::uint64_t u64(const char* field);
  std::string string(const char* field);  // uint32 length prefix
  // `n` bytes: a pointer into the data.
  const std::uint8_t* bytes(std::uint64_t n, const char* field);
  std::map<std::string, std::string> stringMap(const char* field);  // uint32 byte-length prefix
  void skip(std::uint64_t n, const char* field) { bytes(n, field); }

  [[noreturn]] void fail(const std::string& what) const;

 private:
  const std::uint8_t* need(std::uint64_t n, const char* field);
  const std::uint8_t* data_;
  std::size_t size_, pos_ = 0;
  std::string where_;
  std::uint64_t base_;
};

}  // namespace bimloc::sim::ros2
